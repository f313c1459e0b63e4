// The headless runner as a user drives it: runs write complete artefacts; bad input gets exit
// code 2, a message naming the file, the place and the problem, and nothing written.
#include <QtTest>
#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonArray>
#include <QProcess>
#include <QTemporaryDir>

#include "support/Paths.h"

using namespace activetouch;

namespace {
struct Outcome {
    int exitCode;
    QString out, err;
};
Outcome runCli(const QStringList& args) {
    QProcess p;
    p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"), args);
    p.waitForFinished(300000);
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(), p.readAllStandardError()};
}
QString source(const QString& relative) { return QString::fromStdString(test::sourcePath(relative.toStdString())); }
}  // namespace

class TestCli : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

    QString write(const QString& name, const QString& text) {
        QFile f(dir_.filePath(name));
        f.open(QIODevice::WriteOnly);
        f.write(text.toUtf8());
        return f.fileName();
    }

private slots:
    void paperRunWritesSummaryDataAndFigures() {
        const QString out = dir_.filePath("paper");
        const Outcome o = runCli({"run", source("experiments/paper.json"), "--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QFile f(out + "/summary.json");
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject s = QJsonDocument::fromJson(f.readAll()).object();
        const QJsonObject v = s["validation"].toObject();
        for (const char* key : {"angle_error_deg_mean", "position_error_mm_mean", "valid_range_mm", "by_class"}) QVERIFY2(v.contains(key), key);
        QCOMPARE(v["by_class"].toArray().size(), 72);
        QCOMPARE(v["valid_range_mm"].toArray().size(), 2);
        QVERIFY(v["valid_range_mm"].toArray()[0].toDouble() < v["valid_range_mm"].toArray()[1].toDouble());
        const QJsonObject t = s["timing"].toObject();
        QVERIFY(t["wall_s"].toDouble() > 0);
        QCOMPARE(t["taps_simulated"].toInt(), 360);
        for (const char* table : {"taps.csv", "class_regions.csv", "validation_by_class.csv", "validation_by_position.csv", "confusion.csv", "test_percepts.csv"})
            QVERIFY2(QFile::exists(out + "/data/" + table), table);
        // taps.csv: a header plus 50 rows per tap.
        QFile taps(out + "/data/taps.csv");
        QVERIFY(taps.open(QIODevice::ReadOnly));
        QCOMPARE(taps.readAll().count('\n'), 1 + 360 * 50);
        for (const char* figure : {"figure5_taps", "figure6_errors"}) {
            QFile png(out + "/figures/" + figure + ".png"), pdf(out + "/figures/" + figure + ".pdf"), svg(out + "/figures/" + figure + ".svg");
            QVERIFY(png.open(QIODevice::ReadOnly) && pdf.open(QIODevice::ReadOnly) && svg.open(QIODevice::ReadOnly));
            QVERIFY(png.read(8) == QByteArray("\x89PNG\r\n\x1a\n", 8));
            QVERIFY(pdf.read(5) == "%PDF-");
            QVERIFY(svg.readAll().contains("<svg"));
        }
    }

    void seedMakesRunsReproducibleAndDistinct() {
        const QString a = dir_.filePath("a"), b = dir_.filePath("b"), c = dir_.filePath("c");
        QCOMPARE(runCli({"run", source("experiments/paper.json"), "--out", a, "--seed", "5", "--no-figures"}).exitCode, 0);
        QCOMPARE(runCli({"run", source("experiments/paper.json"), "--out", b, "--seed", "5", "--no-figures"}).exitCode, 0);
        QCOMPARE(runCli({"run", source("experiments/paper.json"), "--out", c, "--seed", "6", "--no-figures"}).exitCode, 0);
        auto read = [](const QString& d) { QFile f(d + "/data/taps.csv"); f.open(QIODevice::ReadOnly); return f.readAll(); };
        QVERIFY(read(a) == read(b));
        QVERIFY(read(a) != read(c));
        QVERIFY(!QDir(a + "/figures").exists());
    }

    void checkAcceptsEveryShippedFile() {
        QDir experiments(source("experiments"));
        QStringList files;
        for (const QString& f : experiments.entryList({"*.json"}, QDir::Files)) files << experiments.filePath(f);
        QDir scenes(source("experiments/scenes"));
        for (const QString& f : scenes.entryList({"*.json"}, QDir::Files)) files << scenes.filePath(f);
        QVERIFY(files.size() >= 2);
        for (const QString& f : files) {
            const Outcome o = runCli({"check", f});
            QVERIFY2(o.exitCode == 0, qPrintable(f + ": " + o.err));
        }
    }

    void badInputExitsTwoAndWritesNothing_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("message");
        const QString scene = R"({"object": {"shape": "rectangle", "offset_mm": [150, 150]}, "effects": [EFFECTS]})";
        auto experiment = [&](const QString& effects) {
            QString s = scene;
            s.replace("EFFECTS", effects);
            return QString(R"({"name": "bad", "scene": %1})").arg(s);
        };
        QTest::newRow("malformed JSON") << "broken.json" << R"({"name": "x", "scene": {)" << "line 1, column";
        QTest::newRow("unknown effect") << "effect.json" << experiment(R"({"name": "magic"})") << "/scene/effects/0/name: unknown effect 'magic'";
        QTest::newRow("missing parameter") << "param.json" << experiment(R"({"name": "taxel_noise"})") << "missing required number 'sigma_counts'";
        QTest::newRow("out-of-range parameter") << "range.json" << experiment(R"({"name": "stage_error", "sigma_mm": 9})") << "/scene/effects/0/sigma_mm";
        QTest::newRow("unknown shape") << "shape.json" << R"({"name": "x", "scene": {"object": {"shape": "blob"}}})" << "unknown shape 'blob'";
        QTest::newRow("a scene is not an experiment") << "scene.json" << R"({"object": {"shape": "rectangle"}})" << "not an experiment file";
    }
    void badInputExitsTwoAndWritesNothing() {
        QFETCH(QString, file);
        QFETCH(QString, text);
        QFETCH(QString, message);
        const QString path = write(file, text);
        const QString out = dir_.filePath("out-" + file);
        const Outcome o = runCli({"run", path, "--out", out});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains(path), qPrintable(o.err));
        QVERIFY2(o.err.contains(message), qPrintable(o.err));
        QVERIFY2(!QDir(out).exists(), "output was written for bad input");
        // check says the same.
        const Outcome c = runCli({"check", path});
        if (file != "scene.json") {
            QCOMPARE(c.exitCode, 2);
            QVERIFY2(c.err.contains(message), qPrintable(c.err));
        }
    }

    void usageErrors() {
        QCOMPARE(runCli({}).exitCode, 2);
        QCOMPARE(runCli({"fly"}).exitCode, 2);
        QCOMPARE(runCli({"run"}).exitCode, 2);
        QCOMPARE(runCli({"run", source("experiments/paper.json"), "--seed", "minus"}).exitCode, 2);
        const Outcome help = runCli({"--help"});
        QCOMPARE(help.exitCode, 0);
        QVERIFY(help.out.contains("run <experiment.json>"));
    }
};

QTEST_GUILESS_MAIN(TestCli)
#include "test_cli.moc"
