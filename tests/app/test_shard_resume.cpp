// A shard on a cluster may be killed or pre-empted. Rerun with the same command, it resumes from
// its journal (each seed's outcome appended as it finishes) without redoing the seeds it
// finished, and the shards still merge into exactly what one run over every seed writes. merge
// names the shards that were cut short or are missing ("rerun shards: K"), so that only those are
// resubmitted. A journal of another run, or damaged before its last line, is refused by place.
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

#include "support/Cli.h"
#include "support/Files.h"
#include "support/Paths.h"

using activetouch::test::bytesOf;
using activetouch::test::copyFolder;
using activetouch::test::linesIn;
using activetouch::test::runCli;
using activetouch::test::sourceFile;

class TestShardResume : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    QString paper_, cut_;  ///< a shard folder as a killed run left it
    int done_ = 0;         ///< the seeds its journal holds

    QStringList shardArgs(const QString& shard, const QString& out, const QString& to = "40") {
        return {"seeds", paper_, "--from", "1", "--to",        to, "--shard", shard,
                "--out", out,    "--jobs", "1", "--no-figures"};
    }

private slots:
    void initTestCase() {
        QVERIFY(dir_.isValid());
        paper_ = sourceFile("experiments/paper.json");
        // Shard 1/2 of seeds 1-40, killed (SIGKILL, as a pre-empted job is) once its journal
        // holds two seeds or more.
        const QString live = dir_.filePath("live");
        QProcess p;
        p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"), shardArgs("1/2", live));
        QVERIFY(p.waitForStarted());
        const QString journal = live + "/seed_outcomes.journal";
        while (p.state() == QProcess::Running && linesIn(journal) < 3) QTest::qWait(5);
        QVERIFY2(p.state() == QProcess::Running, "the shard ended before it could be cut short");
        p.kill();
        QVERIFY(p.waitForFinished());
        cut_ = dir_.filePath("cut");
        copyFolder(live, cut_);
        // Whole lines only (a line the kill cut is tried on its own below).
        const QByteArray journalText = bytesOf(cut_ + "/seed_outcomes.journal");
        QFile whole(cut_ + "/seed_outcomes.journal");
        QVERIFY(whole.open(QIODevice::WriteOnly | QIODevice::Truncate));
        whole.write(journalText.left(journalText.lastIndexOf('\n') + 1));
        whole.close();
        done_ = linesIn(cut_ + "/seed_outcomes.journal") - 1;
        QVERIFY(done_ >= 2 && done_ < 20);
    }

    void aKilledShardResumesWithoutRedoingItsSeeds() {
        const QString shard1 = dir_.filePath("shard1");
        copyFolder(cut_, shard1);
        const auto o = runCli(shardArgs("1/2", shard1));
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QVERIFY2(
            o.out.contains(QString("resuming a run cut short: seeds 1-%1 were done").arg(done_)),
            qPrintable(o.out));
        // Only the seeds after the journal's ran: their lines, and no earlier one.
        const QRegularExpression ran(R"(^seed (\d+):)", QRegularExpression::MultilineOption);
        QList<int> seeds;
        for (auto it = ran.globalMatch(o.out); it.hasNext();)
            seeds << it.next().captured(1).toInt();
        QCOMPARE(seeds.size(), 20 - done_);
        QCOMPARE(seeds.front(), done_ + 1);
        QVERIFY(!QFile::exists(shard1 + "/seed_outcomes.journal"));  // the block is whole

        const QString shard2 = dir_.filePath("shard2"), whole = dir_.filePath("whole");
        QCOMPARE(runCli(shardArgs("2/2", shard2)).exitCode, 0);
        QCOMPARE(
            runCli({"seeds", paper_, "--from", "1", "--to", "40", "--out", whole, "--no-figures"})
                .exitCode,
            0);
        const QString merged = dir_.filePath("merged");
        const auto m = runCli({"merge", shard1, shard2, "--out", merged, "--no-figures"});
        QVERIFY2(m.exitCode == 0, qPrintable(m.err));
        for (const char* f : {"rates.csv", "rates.json", "seed_outcomes.json"})
            QVERIFY2(bytesOf(merged + "/" + f) == bytesOf(whole + "/" + f), f);
    }

    void mergeNamesTheShardsToRerun() {
        const QString done = dir_.filePath("shard2_alone");
        QCOMPARE(runCli(shardArgs("2/2", done)).exitCode, 0);
        const auto cut =
            runCli({"merge", cut_, done, "--out", dir_.filePath("m1"), "--no-figures"});
        QCOMPARE(cut.exitCode, 2);
        QVERIFY2(cut.err.contains("were cut short") && cut.err.contains(cut_) &&
                     cut.err.contains("\nrerun shards: 1\n"),
                 qPrintable(cut.err));
        const auto missing = runCli({"merge", done, "--out", dir_.filePath("m2"), "--no-figures"});
        QCOMPARE(missing.exitCode, 2);
        QVERIFY2(missing.err.contains("seeds 1-20 of 1-40 are in no shard given: shards 1/2") &&
                     missing.err.contains("\nrerun shards: 1\n"),
                 qPrintable(missing.err));
    }

    void aCutShortRunOfAnotherRangeIsNotResumed() {
        const QString folder = dir_.filePath("other_range");
        copyFolder(cut_, folder);
        const auto o = runCli(shardArgs("1/2", folder, "41"));
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains("seed_outcomes.journal") && o.err.contains("seeds 1-40") &&
                     o.err.contains("--replace"),
                 qPrintable(o.err));
        QCOMPARE(linesIn(folder + "/seed_outcomes.journal"), done_ + 1);  // nothing lost
    }

    void aDamagedJournalLineIsRefusedAndACutLastLineIsDropped() {
        const QByteArray journal = bytesOf(cut_ + "/seed_outcomes.journal");
        const QList<QByteArray> lines = journal.split('\n');
        // The last outcome cut in the middle, as a kill while writing leaves it: resumed before it.
        const QString cutLine = dir_.filePath("cut_line");
        copyFolder(cut_, cutLine);
        {
            QFile f(cutLine + "/seed_outcomes.journal");
            QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
            f.write(journal.left(journal.size() - lines[lines.size() - 2].size() / 2 - 1));
        }
        const auto resumed = runCli(shardArgs("1/2", cutLine));
        QVERIFY2(resumed.exitCode == 0, qPrintable(resumed.err));
        QVERIFY2(
            resumed.out.contains(QString("seeds 1-%1 were done (from its journal), running %2-20")
                                     .arg(done_ - 1)
                                     .arg(done_)),
            qPrintable(resumed.out));
        // A line before the last damaged: refused by its line, nothing run.
        const QString damaged = dir_.filePath("damaged");
        copyFolder(cut_, damaged);
        {
            QFile f(damaged + "/seed_outcomes.journal");
            QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
            QByteArray edited = journal;
            edited.replace(lines[1], lines[1].left(lines[1].size() / 2) + "\x01" +
                                         lines[1].mid(lines[1].size() / 2 + 1));
            f.write(edited);
        }
        const auto refused = runCli(shardArgs("1/2", damaged));
        QCOMPARE(refused.exitCode, 2);
        QVERIFY2(refused.err.contains("seed_outcomes.journal") && refused.err.contains("line 2"),
                 qPrintable(refused.err));
    }
};

QTEST_GUILESS_MAIN(TestShardResume)
#include "test_shard_resume.moc"
