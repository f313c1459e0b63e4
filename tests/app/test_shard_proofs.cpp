// Shard folders come from other machines: merge believes none of them until each proves itself.
// Its run.json records every file's size and SHA-256, which merge (and replay, analyse and check
// for a run's recordings) verifies; then every outcome is held to what a run can produce, every
// seed to its shard's block and every shard to its place once. Untampered shards still merge
// into exactly what one run writes.
#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>
#include <cctype>
#include <functional>

#include "support/Cli.h"
#include "support/Files.h"
#include "support/Paths.h"

using activetouch::test::bytesOf;
using activetouch::test::copyFolder;
using activetouch::test::runCli;
using activetouch::test::sourceFile;

namespace {

void writeAll(const QString& path, const QByteArray& bytes) {
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) qFatal("cannot write");
    f.write(bytes);
}

/// Records `file`'s new size and digest in `folder`'s run.json, as a forger who knows the format
/// would.
void rehash(const QString& folder, const QString& file) {
    const QByteArray bytes = bytesOf(folder + "/" + file);
    QJsonObject m = QJsonDocument::fromJson(bytesOf(folder + "/run.json")).object();
    QJsonObject files = m["files"].toObject();
    files[file] = QJsonObject{
        {"bytes", bytes.size()},
        {"sha256", QString(QCryptographicHash::hash(bytes, QCryptographicHash::Sha256).toHex())}};
    m["files"] = files;
    writeAll(folder + "/run.json", QJsonDocument(m).toJson());
}

}  // namespace

class TestShardProofs : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    QString shard1_, shard2_, whole_;
    int copies_ = 0;

    /// A copy of shard 1 with its seed_outcomes.json edited by `edit`; rehashed if asked.
    QString tampered(const std::function<void(QJsonObject&)>& edit, bool rehashed) {
        const QString folder = dir_.filePath("tampered_" + QString::number(++copies_));
        copyFolder(shard1_, folder);
        QJsonObject j = QJsonDocument::fromJson(bytesOf(folder + "/seed_outcomes.json")).object();
        edit(j);
        writeAll(folder + "/seed_outcomes.json", QJsonDocument(j).toJson(QJsonDocument::Compact));
        if (rehashed) rehash(folder, "seed_outcomes.json");
        return folder;
    }

    static void setFirstOutcome(QJsonObject& j, const QString& key, const QJsonValue& v) {
        QJsonArray outcomes = j["outcomes"].toArray();
        QJsonObject first = outcomes[0].toObject();
        first[key] = v;
        outcomes[0] = first;
        j["outcomes"] = outcomes;
    }

    void refused(const QStringList& folders, const QString& named, const QString& what) {
        QStringList args{"merge"};
        args << folders << "--out" << dir_.filePath("refused_" + QString::number(++copies_))
             << "--no-figures";
        const auto o = runCli(args);
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains(named) && o.err.contains(what), qPrintable(o.err));
    }

private slots:
    void initTestCase() {
        QVERIFY(dir_.isValid());
        const QString paper = sourceFile("experiments/paper.json");
        shard1_ = dir_.filePath("shard1");
        shard2_ = dir_.filePath("shard2");
        whole_ = dir_.filePath("whole");
        for (const auto& [out, shard] : {std::pair{shard1_, QString("1/2")}, {shard2_, "2/2"}}) {
            const auto o = runCli({"seeds", paper, "--from", "1", "--to", "4", "--shard", shard,
                                   "--out", out, "--no-figures"});
            QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        }
        const auto o =
            runCli({"seeds", paper, "--from", "1", "--to", "4", "--out", whole_, "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
    }

    void everyFileIsRecordedWithItsDigest() {
        const QJsonObject m = QJsonDocument::fromJson(bytesOf(shard1_ + "/run.json")).object();
        const QJsonObject entry = m["files"].toObject()["seed_outcomes.json"].toObject();
        const QByteArray bytes = bytesOf(shard1_ + "/seed_outcomes.json");
        QCOMPARE(entry["bytes"].toInteger(), qint64(bytes.size()));
        QCOMPARE(entry["sha256"].toString(),
                 QString(QCryptographicHash::hash(bytes, QCryptographicHash::Sha256).toHex()));
    }

    void untamperedShardsMergeIntoWhatOneRunWrites() {
        const QString merged = dir_.filePath("merged");
        const auto o = runCli({"merge", shard2_, shard1_, "--out", merged, "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        for (const char* f : {"rates.csv", "rates.json", "seed_outcomes.json"})
            QVERIFY2(bytesOf(merged + "/" + f) == bytesOf(whole_ + "/" + f), f);
    }

    void anEditedShardFileIsRefusedByItsDigest() {
        // One digit of a count changed in place: the same size, another digest.
        const QString folder = dir_.filePath("edited");
        copyFolder(shard1_, folder);
        QByteArray text = bytesOf(folder + "/seed_outcomes.json");
        const int key = text.indexOf("\"active_completed\":");
        QVERIFY(key > 0);
        int digit = key + int(qstrlen("\"active_completed\":"));
        while (text[digit] == ' ') ++digit;
        QVERIFY(std::isdigit(static_cast<unsigned char>(text[digit])));
        text[digit] = text[digit] == '9' ? '8' : char(text[digit] + 1);
        writeAll(folder + "/seed_outcomes.json", text);
        refused({folder, shard2_}, folder + "/seed_outcomes.json", "SHA-256 differs");
        // Rewritten whole, its size gives it away first.
        const QString rewritten =
            tampered([](QJsonObject& j) { setFirstOutcome(j, "active_completed", 132); }, false);
        refused({rewritten, shard2_}, rewritten + "/seed_outcomes.json", "was written to since");
    }

    void outcomesThatNoRunWritesAreRefusedEvenWithTheirDigestsForged_data() {
        QTest::addColumn<QString>("key");
        QTest::addColumn<double>("value");
        QTest::addColumn<QString>("what");
        QTest::newRow("completed above trials")
            << "active_completed" << 132.0 << "is more than its active_trials";
        QTest::newRow("negative trials") << "passive_trials" << -4.0 << "is below 0";
        QTest::newRow("centuries of robot time")
            << "run_robot_time_s" << 1e308 << "is not a finite value within 0..";
        QTest::newRow("negative time")
            << "completed_robot_time_s" << -1.0 << "is not a finite value within 0..";
        QTest::newRow("angle error past 180")
            << "angle_error_deg" << 500.0 << "is not a finite value within 0..180";
    }
    void outcomesThatNoRunWritesAreRefusedEvenWithTheirDigestsForged() {
        QFETCH(QString, key);
        QFETCH(double, value);
        QFETCH(QString, what);
        const QString folder =
            tampered([&](QJsonObject& j) { setFirstOutcome(j, key, value); }, true);
        refused({folder, shard2_}, folder + "/seed_outcomes.json: at /outcomes/0/" + key, what);
    }

    void aResizedShardIsRefused() {
        // One seed's outcome dropped, the digest forged: its block holds two seeds.
        const QString folder = tampered(
            [](QJsonObject& j) {
                QJsonArray outcomes = j["outcomes"].toArray();
                outcomes.removeLast();
                j["outcomes"] = outcomes;
            },
            true);
        refused({folder, shard2_}, folder, "holds 1 seeds' outcomes, but its block as shard 1/2");
        // A seed moved outside its shard's block.
        const QString moved = tampered([](QJsonObject& j) { setFirstOutcome(j, "seed", 4); }, true);
        refused({moved, shard2_}, moved, "holds seed 4, but as shard 1/2 of 1-4 its block is");
    }

    void twoFoldersClaimingOneShardAreRefused() {
        const QString twin = dir_.filePath("twin");
        copyFolder(shard1_, twin);
        refused({shard1_, twin, shard2_}, twin, "both claim shard 1/2");
    }

    void anotherRunsManifestIsRefused() {
        // Shard 1's files beside shard 2's run.json: its digests are of other files.
        const QString swapped = dir_.filePath("swapped");
        copyFolder(shard1_, swapped);
        QFile::remove(swapped + "/run.json");
        QFile::copy(shard2_ + "/run.json", swapped + "/run.json");
        refused({swapped, shard2_}, swapped, "/run.json): it was written to since");
        // A shard folder without its run.json proves nothing.
        const QString bare = dir_.filePath("bare");
        copyFolder(shard1_, bare);
        QFile::remove(bare + "/run.json");
        refused({bare, shard2_}, bare + "/run.json", "there is no run.json");
    }

    void foldersFromBeforeDigestsAreReadButNotMerged() {
        // A run.json that records bare sizes, as folders written before digests were kept do: a
        // recording in it is still read (its sizes checked), a shard is not merged.
        auto bareSizes = [](const QString& folder) {
            QJsonObject m = QJsonDocument::fromJson(bytesOf(folder + "/run.json")).object();
            QJsonObject files = m["files"].toObject();
            for (const QString& k : files.keys()) files[k] = files[k].toObject()["bytes"];
            m["files"] = files;
            writeAll(folder + "/run.json", QJsonDocument(m).toJson());
        };
        const QString run = dir_.filePath("earlier_run");
        const auto made =
            runCli({"run", sourceFile("experiments/paper.json"), "--out", run, "--no-figures"});
        QVERIFY2(made.exitCode == 0, qPrintable(made.err));
        bareSizes(run);
        const auto checked = runCli({"check", run + "/data/taps.csv"});
        QVERIFY2(checked.exitCode == 0, qPrintable(checked.err));
        const QString earlier = dir_.filePath("earlier_shard");
        copyFolder(shard1_, earlier);
        bareSizes(earlier);
        refused({earlier, shard2_}, earlier + "/run.json", "records only the size");
    }

    void aRecordingChangedInPlaceIsRefusedByCheckAndReplay() {
        // Same size, one digit changed: only the digest shows it.
        const QString run = dir_.filePath("run");
        const auto made =
            runCli({"run", sourceFile("experiments/paper.json"), "--out", run, "--no-figures"});
        QVERIFY2(made.exitCode == 0, qPrintable(made.err));
        QByteArray taps = bytesOf(run + "/data/taps.csv");
        // The last digit of the first row: the last place of its last taxel's reading.
        const int rowEnd = taps.indexOf('\n', taps.indexOf('\n') + 1);
        QVERIFY(rowEnd > 0 && std::isdigit(static_cast<unsigned char>(taps[rowEnd - 1])));
        taps[rowEnd - 1] = taps[rowEnd - 1] == '9' ? '8' : char(taps[rowEnd - 1] + 1);
        writeAll(run + "/data/taps.csv", taps);
        const auto checked = runCli({"check", run + "/data/taps.csv"});
        QCOMPARE(checked.exitCode, 2);
        QVERIFY2(checked.err.contains("taps.csv") && checked.err.contains("SHA-256 differs"),
                 qPrintable(checked.err));
        const auto replayed = runCli({"replay", sourceFile("experiments/paper.json"), run, "--out",
                                      dir_.filePath("replayed"), "--no-figures"});
        QCOMPARE(replayed.exitCode, 2);
        QVERIFY2(replayed.err.contains("SHA-256 differs"), qPrintable(replayed.err));
    }
};

QTEST_GUILESS_MAIN(TestShardProofs)
#include "test_shard_proofs.moc"
