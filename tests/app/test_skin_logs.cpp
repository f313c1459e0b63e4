// Skin logs from YARP's data dumper: a run's taps logged as a dumper would, imported with the
// fingertip's taxel map and the stage's pose log, give a recording whose analysis is the run's
// validation to the last digit; bad maps, logs and pose logs are refused by line, writing
// nothing; without a pose log taps are found by the reflex threshold.
#include <QTextStream>

#include "CliFixture.h"
#include "core/experiment/Experiment.h"
#include "core/records/DumperLog.h"
#include "core/records/TapCutting.h"
#include "core/records/TapCsv.h"

class TestSkinLogs : public CliFixture {
    Q_OBJECT

    QString paper_, logDir_, map_;

    static QStringList lines(const QString& path) {
        QFile f(path);
        if (!f.open(QIODevice::ReadOnly)) return {};
        return QString(f.readAll()).split('\n', Qt::SkipEmptyParts);
    }

    /// Copies the paper run's dumper folder under `name` with `edit` applied to its data.log,
    /// poses.log or map lines; returns the folder.
    QString editedCopy(const QString& name,
                       const std::function<void(QStringList&, QStringList&, QStringList&)>& edit) {
        QStringList data = lines(logDir_ + "/data.log"), poses = lines(logDir_ + "/poses.log"),
                    map = lines(map_);
        edit(data, poses, map);
        QDir().mkpath(dir_.filePath(name));
        write(name + "/data.log", data.join('\n') + (name == "truncated" ? "" : "\n"));
        write(name + "/poses.log", poses.join('\n') + '\n');
        write(name + "/map.txt", map.join('\n') + '\n');
        return dir_.filePath(name);
    }

private slots:
    void initTestCase() {
        paper_ = sourceFile("experiments/paper.json");
        const Outcome o = runCli({"run", paper_, "--out", dir_.filePath("paper"), "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        // The run's taps as the middle finger of a right hand's 192-value skin port would log
        // them, with the stage's pose log beside.
        const ExperimentSpec spec = loadExperiment(paper_.toStdString());
        const auto taps =
            readTapCsv(dir_.filePath("paper/data/taps.csv").toStdString(), spec.classes);
        std::vector<TapRecord> records;
        for (const auto& t : taps) records.push_back(t.record);
        TaxelMap map;
        map.valuesPerFrame = 192;
        for (int k = 0; k < 12; ++k) map.valueOf.push_back(12 + k);
        logDir_ = dir_.filePath("dumper");
        writeDumperLog(logDir_.toStdString(), records, map, spec.scene.tap.sampleRate_hz);
        map_ = write("middle.map",
                     "# the right hand's middle fingertip\nvalues_per_frame 192\n"
                     "finger middle\n");
    }

    void anImportedDumperLogGivesTheRunsValidationAgain() {
        const QString out = dir_.filePath("imported");
        const Outcome o = runCli({"import", paper_, logDir_, "--taxel-map", map_, "--poses",
                                  logDir_ + "/poses.log", "--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QVERIFY2(o.out.contains("360 taps cut by the pose log") && o.out.contains("of the 360"),
                 qPrintable(o.out));
        const QJsonObject info = readJson(out + "/import.json");
        QCOMPARE(info["taps"].toInt(), 360);
        QCOMPARE(info["frames_missing"].toInt(), 0);
        QCOMPARE(info["stamps_per_line"].toInt(), 1);
        QCOMPARE(info["taxel_values"].toArray().first().toInt(), 12);

        // Every sample, pose, time and offset of the run's recording comes back; how each tap
        // ended is read from the reflex threshold over the recorded pressures. A skin log holds
        // no tapper, so no stop depth is recorded (0).
        const QStringList run = lines(dir_.filePath("paper/data/taps.csv"));
        const QStringList imported = lines(out + "/data/taps.csv");
        QCOMPARE(imported.size(), run.size());
        int endingsDiffer = 0;
        for (int i = 0; i < run.size(); ++i) {
            QStringList a = run[i].split(','), b = imported[i].split(',');
            QCOMPARE(b.size(), a.size());
            if (a[8] != b[8]) ++endingsDiffer;
            if (i > 0) QCOMPARE(b[9], QString("0"));
            for (QStringList* row : {&a, &b}) {
                row->removeAt(9);
                row->removeAt(8);
            }
            QVERIFY2(a == b,
                     qPrintable(QString("line %1:\n%2\n%3").arg(i + 1).arg(run[i], imported[i])));
        }
        QVERIFY2(endingsDiffer < run.size() / 10, qPrintable(QString::number(endingsDiffer)));

        const QString analysis = dir_.filePath("imported_analysis");
        const Outcome a =
            runCli({"analyse", paper_, out + "/data/taps.csv", "--out", analysis, "--no-figures"});
        QVERIFY2(a.exitCode == 0, qPrintable(a.err));
        const QJsonObject before = readJson(dir_.filePath("paper/summary.json"));
        const QJsonObject after = readJson(analysis + "/summary.json");
        QVERIFY(!before["validation"].toObject().isEmpty());
        QCOMPARE(after["validation"].toObject(), before["validation"].toObject());
        QCOMPARE(after["class_regions"], before["class_regions"]);
    }

    void anotherFingersMapIsRefusedNamingTheFingerThatTouched() {
        // The map decides which values are read: the index finger's are the resting zeros while
        // the middle finger's press, so every tap would read nothing: refused, naming both.
        const QString indexMap = write("index.map", "values_per_frame 192\nfinger index\n");
        const QString out = dir_.filePath("imported_index");
        const Outcome o = runCli({"import", paper_, logDir_, "--taxel-map", indexMap, "--poses",
                                  logDir_ + "/poses.log", "--out", out});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.startsWith("error: " + indexMap) && o.err.contains("the middle finger's") &&
                     o.err.contains("another fingertip than the one that touched"),
                 qPrintable(o.err));
        QVERIFY(!QFile::exists(out));
    }

    void withoutAPoseLogTapsThatTouchNothingCannotBeMatched() {
        const Outcome o = runCli(
            {"import", paper_, logDir_, "--taxel-map", map_, "--out", dir_.filePath("no_poses")});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains("--poses") && o.err.contains("protocol takes 360"),
                 qPrintable(o.err));
        QVERIFY(!QFile::exists(dir_.filePath("no_poses")));
    }

    void dumpWritesALogThatImportReadsBack() {
        const QString folder = dir_.filePath("dumped");
        const Outcome d = runCli({"dump", paper_, dir_.filePath("paper/data/taps.csv"),
                                  "--taxel-map", map_, "--out", folder});
        QVERIFY2(d.exitCode == 0, qPrintable(d.err));
        QVERIFY2(d.out.contains("360 taps"), qPrintable(d.out));
        QFile a(folder + "/data.log"), b(logDir_ + "/data.log");
        QVERIFY(a.open(QIODevice::ReadOnly) && b.open(QIODevice::ReadOnly));
        QVERIFY(a.readAll() == b.readAll());
        // A folder already holding a log is not written over without --replace.
        const Outcome again = runCli({"dump", paper_, dir_.filePath("paper/data/taps.csv"),
                                      "--taxel-map", map_, "--out", folder});
        QCOMPARE(again.exitCode, 2);
        QVERIFY2(again.err.contains("already holds a data.log"), qPrintable(again.err));
    }

    void calibrateFitsARunsTapsAndRefusesWhatItCannot() {
        const QString out = dir_.filePath("fitted/paper_fitted.json");
        const Outcome o = runCli(
            {"calibrate", paper_, dir_.filePath("paper"), "--out", out, "--replicates", "5"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QVERIFY2(o.out.contains("taxel_noise          yes") &&
                     o.out.contains("adc_quantisation     yes") &&
                     o.out.contains("contact_latency      yes") &&
                     o.out.contains("Figure 6 recorded"),
                 qPrintable(o.out));
        const QJsonObject report = readJson(dir_.filePath("fitted/paper_fitted.calibration.json"));
        QCOMPARE(report["taps"].toInt(), 360);
        QCOMPARE(report["bootstrap_replicates"].toInt(), 5);
        QCOMPARE(report["goodness_of_fit"].toArray().size(), 12);
        QVERIFY(report["figure6"].toObject()["simulated_recordings"].toInt() > 0);
        // The fitted scene is a scene: check reads it, and the paper runs on it.
        const Outcome check = runCli({"check", out});
        QVERIFY2(check.exitCode == 0, qPrintable(check.err + check.out));
        QVERIFY(QFileInfo(dir_.filePath("fitted/paper_fitted.simulated_taps.csv")).size() > 0);
        for (const char* ext : {"png", "pdf", "svg"})
            QVERIFY2(QFileInfo(dir_.filePath("fitted/paper_fitted.calibration.") + ext).size() > 0,
                     ext);

        const Outcome twice = runCli({"calibrate", paper_, dir_.filePath("paper"), "--out", out});
        QCOMPARE(twice.exitCode, 2);
        QVERIFY2(twice.err.contains("already exists") && twice.err.contains("--replace"),
                 qPrintable(twice.err));
        // --no-figures writes the scene and its report without the figure.
        const QString bare = dir_.filePath("fitted/bare.json");
        const Outcome noFigures = runCli({"calibrate", paper_, dir_.filePath("paper"), "--out",
                                          bare, "--replicates", "5", "--no-figures"});
        QVERIFY2(noFigures.exitCode == 0, qPrintable(noFigures.err));
        QVERIFY(QFile::exists(bare) &&
                !QFile::exists(dir_.filePath("fitted/bare.calibration.png")));
        const Outcome noOut = runCli({"calibrate", paper_, dir_.filePath("paper")});
        QCOMPARE(noOut.exitCode, 2);
        QVERIFY2(noOut.err.contains("--out"), qPrintable(noOut.err));
        const Outcome missing = runCli({"calibrate", paper_, dir_.filePath("nowhere"), "--out",
                                        dir_.filePath("fitted/none.json")});
        QCOMPARE(missing.exitCode, 2);
        QVERIFY2(missing.err.startsWith("error: ") && missing.err.contains("nowhere"),
                 qPrintable(missing.err));
        QVERIFY(!QFile::exists(dir_.filePath("fitted/none.json")));
        // An --out that cannot be written is said before the fit, as a run that failed (1).
        const QString aFile = write("not_a_folder", "x");
        const Outcome unwritable = runCli(
            {"calibrate", paper_, dir_.filePath("paper"), "--out", aFile + "/fitted.json"});
        QCOMPARE(unwritable.exitCode, 1);
        QVERIFY2(unwritable.err.startsWith("error: ") && unwritable.err.contains(aFile) &&
                     unwritable.err.contains("Nothing was fitted"),
                 qPrintable(unwritable.err));
        QVERIFY2(!unwritable.out.contains("samples over nothing"), "the fit ran first");
        // What the fit refuses about the taps names the recording, not the scene.
        QStringList few = lines(dir_.filePath("paper/data/taps.csv")).mid(0, 1 + 5 * 50);
        const QString fewTaps = write("few_taps.csv", few.join('\n') + '\n');
        const Outcome tooFew = runCli(
            {"calibrate", paper_, fewTaps, "--out", dir_.filePath("fitted/few.json")});
        QCOMPARE(tooFew.exitCode, 2);
        QVERIFY2(tooFew.err.startsWith("error: " + fewTaps) &&
                     tooFew.err.contains("at least 20 recorded taps; the recording has 5"),
                 qPrintable(tooFew.err));
    }

    void theReflexThresholdFindsTapsThatTouch() {
        // A stream of three taps that touch, between resting frames: each is found where its total
        // pressure crosses the threshold, its window starting the lead before.
        SkinStream s;
        s.taxels = 2;
        const int T = 10;
        std::vector<int> starts{5, 30, 47};
        for (int f = 0; f < 70; ++f) {
            s.counters.push_back(static_cast<std::uint64_t>(100 + f));
            s.times_s.push_back(f * 0.02);
            s.lines.push_back(f + 1);
            double v = 0.5;  // noise below the threshold
            for (int start : starts)
                if (f >= start + 3 && f < start + 8) v = 30.0 + f;  // contact from frame 3 on
            s.values.push_back(v);
            s.values.push_back(v);
        }
        TapCutting c;
        c.samplesPerTap = T;
        c.reflexThreshold = 40.0;
        c.leadFrames = 3;
        const auto taps = cutTaps(s, nullptr, c, "log", "");
        QCOMPARE(taps.size(), starts.size());
        for (std::size_t i = 0; i < taps.size(); ++i) {
            QCOMPARE(taps[i].startTime_s, starts[i] * 0.02);
            QCOMPARE(taps[i].tap.at(3, 0), 30.0 + starts[i] + 3);
            QVERIFY(taps[i].ending == TapEnding::ContactReflex);
        }
        // A stream ending inside the last window: that tap is left out and said so.
        SkinStream shorter = s;
        const std::size_t keep = 47 + 6;
        shorter.counters.resize(keep);
        shorter.times_s.resize(keep);
        shorter.lines.resize(keep);
        shorter.values.resize(keep * 2);
        std::string cut;
        QCOMPARE(cutTaps(shorter, nullptr, c, "log", "", &cut).size(), 2u);
        QVERIFY2(cut.find("line 51") != std::string::npos, cut.c_str());
        QVERIFY_THROWS_EXCEPTION(InputError, cutTaps(shorter, nullptr, c, "log", ""));
    }

    void badLogsMapsAndPoseLogsAreRefusedByLine_data() {
        QTest::addColumn<QString>("edit");
        QTest::addColumn<QString>("file");  // the file the message names
        QTest::addColumn<QString>("expected");
        QTest::newRow("shuffled map") << "shuffled map"
                                      << "map.txt"
                                      << "line 2: taxel 1 where taxel 0 comes next";
        QTest::newRow("a value read twice") << "value twice"
                                            << "map.txt"
                                            << "line 3: value 12 is already taxel 0's";
        QTest::newRow("a taxel missing") << "taxel missing"
                                         << "map.txt"
                                         << "the map ends after 11 taxels";
        QTest::newRow("a value past the frame") << "value past"
                                                << "map.txt"
                                                << "value 192 lies past the frame's 192";
        QTest::newRow("a missing value") << "missing value"
                                         << "data.log"
                                         << "line 7: the frame has 191 values where 192";
        QTest::newRow("a non-numeric field") << "non-numeric"
                                             << "data.log"
                                             << "line 9, value 17: 'n/a' is not a finite number";
        QTest::newRow("time running backwards") << "backwards"
                                                << "data.log"
                                                << "line 20, stamp: the stamp";
        QTest::newRow("a counter that falls") << "counter"
                                              << "data.log"
                                              << "line 30, counter: counter 2 after 28";
        QTest::newRow("a counter that jumps past its stamps") << "counter jump"
                                                              << "data.log"
                                                              << "line 30, counter: counter "
                                                                 "1000000000000000 after 28 skips";
        QTest::newRow("a pose time below zero") << "pose negative"
                                                << "poses.log"
                                                << "line 2, column time_s: robot time -5 s is "
                                                   "negative";
        QTest::newRow("a value past the skin's range") << "range"
                                                       << "data.log"
                                                       << "line 5, value 14: 300 is outside";
        QTest::newRow("a truncated last line") << "truncated"
                                               << "data.log"
                                               << "the dumper stopped while writing it";
        QTest::newRow("a frame missing inside a tap") << "gap"
                                                      << "data.log"
                                                      << "lacks a frame";
        QTest::newRow("a pose log of another placement") << "moved"
                                                         << "poses.log"
                                                         << "line 6: tap 5 was taken at";
        QTest::newRow("a pose line that is no number") << "pose text"
                                                       << "poses.log"
                                                       << "line 3, y_mm: 'abc'";
        QTest::newRow("a pose log past the skin log") << "pose past"
                                                      << "poses.log"
                                                      << "ends at";
    }

    void badLogsMapsAndPoseLogsAreRefusedByLine() {
        QFETCH(QString, edit);
        QFETCH(QString, file);
        QFETCH(QString, expected);
        const QString folder = editedCopy(
            edit == "truncated" ? "truncated" : "edited_" + QString(edit).replace(' ', '_'),
            [&](QStringList& data, QStringList& poses, QStringList& map) {
                if (edit == "shuffled map" || edit == "value twice" || edit == "taxel missing" ||
                    edit == "value past") {
                    map = {"values_per_frame 192"};
                    for (int k = 0; k < 12; ++k)
                        map << QString("taxel %1 value %2").arg(k).arg(12 + k);
                    if (edit == "shuffled map") map.swapItemsAt(1, 2);
                    if (edit == "value twice") map[2] = "taxel 1 value 12";
                    if (edit == "taxel missing") map.removeLast();
                    if (edit == "value past") map[5] = "taxel 4 value 192";
                }
                auto setField = [&](int line, int f, const QString& v) {
                    QStringList parts = data[line - 1].split(' ');
                    parts[f] = v;
                    data[line - 1] = parts.join(' ');
                };
                if (edit == "missing value") {
                    QStringList parts = data[6].split(' ');
                    parts.removeLast();
                    data[6] = parts.join(' ');
                }
                if (edit == "non-numeric") setField(9, 2 + 17, "n/a");
                if (edit == "backwards") setField(20, 1, "0.000000");
                if (edit == "counter") setField(30, 0, "2");
                if (edit == "counter jump") setField(30, 0, "1000000000000000");
                if (edit == "pose negative") {
                    QStringList p = poses[1].split(' ');  // the first after the comment
                    p[p.size() - 3] = "-5";
                    poses[1] = p.join(' ');
                }
                if (edit == "range") setField(5, 2 + 14, "300");
                if (edit == "truncated") data.last() = data.last().left(data.last().size() / 2);
                if (edit == "gap") data.removeAt(20);  // inside the first tap's window
                if (edit == "moved") {
                    QStringList p = poses[5].split(' ');
                    p[1] = QString::number(p[1].toDouble() + 10.0, 'g', 17);
                    poses[5] = p.join(' ');
                }
                if (edit == "pose text") {
                    QStringList p = poses[2].split(' ');
                    p[2] = "abc";
                    poses[2] = p.join(' ');
                }
                if (edit == "pose past")
                    poses << "99999 150 150"
                          << "99999.5 150 150";
            });
        const QString out = dir_.filePath("refused_import");
        const Outcome o = runCli({"import", paper_, folder, "--taxel-map", folder + "/map.txt",
                                  "--poses", folder + "/poses.log", "--out", out});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.startsWith("error: ") && o.err.contains(folder + "/" + file) &&
                     o.err.contains(expected),
                 qPrintable(o.err));
        QVERIFY(!QFile::exists(out));  // nothing written
    }
};

QTEST_GUILESS_MAIN(TestSkinLogs)
#include "test_skin_logs.moc"
