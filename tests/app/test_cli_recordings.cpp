// analyse and replay from the command line: a run's recording re-analysed gives its
// validation again; replayed with its own settings it retraces every trial, with others it says
// where each left; recordings that cannot be validated or replayed are refused.
#include "CliFixture.h"

class TestCliRecordings : public CliFixture {
    Q_OBJECT

private slots:
    void initTestCase() {
        // The recording every test here reads: the paper run, as the command line writes it.
        const Outcome o = runCli({"run", sourceFile("experiments/paper.json"), "--out",
                                  dir_.filePath("paper"), "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
    }

    void analyseReanalysesARecording() {
        // The paper run's recording (initTestCase) re-analysed with
        // the same experiment gives the same validation, from the taps alone.
        const QString recording = dir_.filePath("paper/data/taps.csv");
        QVERIFY(QFile::exists(recording));
        const QString out = dir_.filePath("analysis");
        const Outcome o =
            runCli({"analyse", sourceFile("experiments/paper.json"), recording, "--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QVERIFY2(o.out.contains("360 recorded taps"), qPrintable(o.out));
        const QJsonObject run = readJson(dir_.filePath("paper/summary.json"));
        const QJsonObject again = readJson(out + "/summary.json");
        for (const char* key :
             {"angle_error_deg_mean", "position_error_mm_mean", "valid_range_mm", "by_class"})
            QVERIFY2(again["validation"].toObject()[key] == run["validation"].toObject()[key], key);
        QCOMPARE(again["rig"].toString(), "recording " + recording);
        QCOMPARE(again["following"].toArray().size(), 0);
        for (const char* figure : {"figure5_taps", "figure6_errors"})
            QVERIFY2(QFileInfo(out + "/figures/" + figure + ".png").size() > 0, figure);
        QVERIFY(!QFile::exists(out + "/figures/figure8_active_paths.png"));
        QFile in(recording), copy(out + "/data/taps.csv");
        QVERIFY(in.open(QIODevice::ReadOnly) && copy.open(QIODevice::ReadOnly));
        QVERIFY(in.readAll() == copy.readAll());

        // Retrained on every set for following: the same validation, and the run says what its
        // trials would follow with.
        const QString outRetrained = dir_.filePath("analysis_retrained");
        const Outcome retrained = runCli({"analyse", sourceFile("experiments/paper_retrained.json"),
                                          recording, "--out", outRetrained, "--no-figures"});
        QVERIFY2(retrained.exitCode == 0, qPrintable(retrained.err));
        QVERIFY2(retrained.out.contains("following classifier: trained again after validation on "
                                        "all 5 data sets (360 taps, test sets included)"),
                 qPrintable(retrained.out));
        QVERIFY(!o.out.contains("following classifier"));
        const QJsonObject r = readJson(outRetrained + "/summary.json");
        QCOMPARE(r["validation"].toObject()["by_class"], run["validation"].toObject()["by_class"]);
        QCOMPARE(r["training"].toObject()["retrain_on_all_sets"].toBool(), true);
        QCOMPARE(run["training"].toObject()["retrain_on_all_sets"].toBool(true), false);

        // Other classifier settings on the same taps: another validation.
        const QString coarse = write("coarse.json", QString(R"({"extends": "%1",
            "classifier": {"bins": 10}})")
                                                        .arg(sourceFile("experiments/paper.json")));
        const QString outCoarse = dir_.filePath("analysis_coarse");
        QCOMPARE(
            runCli({"analyse", coarse, recording, "--out", outCoarse, "--no-figures"}).exitCode, 0);
        const QJsonObject c = readJson(outCoarse + "/summary.json");
        QVERIFY(c["validation"].toObject()["by_class"] != run["validation"].toObject()["by_class"]);

        // Of the sweeps, (c) runs on the recorded taps; (a) and (b) need a rig and are said so.
        const QString swept = write("swept.json", QString(R"({"extends": "%1",
            "sweeps": {"compute": {"bins": [20, 100], "samples_per_tap": [25, 50]},
                       "perception": {"belief_thresholds": [0.5]}}})")
                                                      .arg(sourceFile("experiments/paper.json")));
        const QString outSwept = dir_.filePath("analysis_swept");
        const Outcome s = runCli({"analyse", swept, recording, "--out", outSwept});
        QVERIFY2(s.exitCode == 0, qPrintable(s.err));
        QVERIFY2(s.out.contains("sweeps (a) and (b)"), qPrintable(s.out));
        const QJsonObject sw = readJson(outSwept + "/summary.json")["sweeps"].toObject();
        QCOMPARE(sw["compute"].toArray().size(), 4);
        QCOMPARE(sw["perception"].toArray().size(), 0);
        QVERIFY(QFileInfo(outSwept + "/figures/sweep_c_compute.png").size() > 0);
        QVERIFY(!QFile::exists(outSwept + "/figures/sweep_a_sequential_perception.png"));
    }

    void analyseRefusesRecordingsItCannotValidate_data() {
        QTest::addColumn<QString>("edit");  // what to do to the paper run's recording
        QTest::addColumn<QString>("expected");
        QTest::newRow("a class without a training tap") << "drop set 1 class 0"
                                                        << "training set 1 has no tap of class 0";
        QTest::newRow("other classes") << "orientation 45"
                                       << "recorded with other classes";
        QTest::newRow("a data set the experiment lacks") << "set 7"
                                                         << "data set 7 is not one";
        QTest::newRow("only training taps") << "all set 1"
                                            << "nothing is left to validate on";
        QTest::newRow("no such file") << "missing"
                                      << "no such file";
    }

    void analyseRefusesRecordingsItCannotValidate() {
        QFETCH(QString, edit);
        QFETCH(QString, expected);
        QFile in(dir_.filePath("paper/data/taps.csv"));
        QVERIFY(in.open(QIODevice::ReadOnly));
        QStringList rows = QString(in.readAll()).split('\n', Qt::SkipEmptyParts);
        QStringList kept{rows.takeFirst()};
        for (const QString& row : rows) {
            QStringList f = row.split(',');
            if (edit == "drop set 1 class 0" && f[0] == "1" && f[1] == "0") continue;
            if (edit == "orientation 45" && f[1] == "3") f[2] = "45";
            if (edit == "set 7" && f[0] == "5") f[0] = "7";
            if (edit == "all set 1") f[0] = "1";
            kept << f.join(',');
        }
        const QString recording = edit == "missing" ? dir_.filePath("nowhere/taps.csv")
                                                    : write("edited_taps.csv", kept.join('\n'));
        const QString out = dir_.filePath("refused_analysis");
        const Outcome o = runCli({"analyse", sourceFile("experiments/paper.json"), recording,
                                  "--out", out, "--no-figures"});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains(expected) && o.err.contains(recording), qPrintable(o.err));
        QVERIFY(!QFile::exists(out));  // nothing written
    }

    void replayRetracesARunsRecording() {
        // The paper run (paperRunWritesSummaryDataAndFigures, above) replayed as a rig with its own
        // experiment: every trial is served the recorded taps and retraces them to the same end.
        const QString run = dir_.filePath("paper");
        const QString out = dir_.filePath("replay");
        const Outcome o =
            runCli({"replay", sourceFile("experiments/paper.json"), run, "--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        const QJsonObject recorded = readJson(run + "/summary.json");
        const QJsonObject again = readJson(out + "/summary.json");
        QCOMPARE(again["rig"].toString(), "replay of " + run);
        const QJsonArray before = recorded["following"].toArray(),
                         after = again["following"].toArray();
        QCOMPARE(after.size(), 10);
        QCOMPARE(after.size(), before.size());
        for (int i = 0; i < after.size(); ++i) {
            const QJsonObject a = after[i].toObject(), b = before[i].toObject();
            for (const char* key : {"shape", "mode", "trial", "completed", "reason", "taps",
                                    "coverage", "mean_contour_distance_mm", "start_mm"})
                QVERIFY2(a[key] == b[key], qPrintable(QString("trial %1, %2").arg(i).arg(key)));
            QCOMPARE(a["recorded_taps"].toInt(), b["taps"].toInt());
            QVERIFY2(
                o.out.contains(QString("%1 of %1 recorded taps retraced").arg(a["taps"].toInt())),
                qPrintable(o.out));
        }
        QVERIFY(again["recognition"].toObject()["trials"] ==
                recorded["recognition"].toObject()["trials"]);
        // The replay's own recording holds the same taps.
        QFile in(run + "/data/following_taps.csv"), copy(out + "/data/following_taps.csv");
        QVERIFY(in.open(QIODevice::ReadOnly) && copy.open(QIODevice::ReadOnly));
        QVERIFY(in.readAll() == copy.readAll());
        QVERIFY(QFileInfo(out + "/figures/figure8_active_paths.png").size() > 0);
    }

    void replayReadsRecordingsThatSpeltShapesInLowerCase() {
        // Recordings from before the library named its shapes C and L call their trials c and l.
        const QString run = dir_.filePath("paper");
        const QString older = dir_.filePath("lower_case_labels");
        QVERIFY(QDir().mkpath(older + "/data"));
        QVERIFY(QFile::copy(run + "/data/taps.csv", older + "/data/taps.csv"));
        QFile in(run + "/data/following_taps.csv"), out(older + "/data/following_taps.csv");
        QVERIFY(in.open(QIODevice::ReadOnly) && out.open(QIODevice::WriteOnly));
        int lowered = 0;
        while (!in.atEnd()) {
            QByteArray line = in.readLine();
            if (line.startsWith("C,") || line.startsWith("L,"))
                line[0] = char(line[0] + 32), ++lowered;
            out.write(line);
        }
        out.close();
        QVERIFY(lowered > 0);
        const QString replayed = dir_.filePath("lower_case_replay");
        const Outcome o = runCli({"replay", sourceFile("experiments/paper.json"), older, "--out",
                                  replayed, "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        const QJsonArray before = readJson(run + "/summary.json")["following"].toArray(),
                         after = readJson(replayed + "/summary.json")["following"].toArray();
        QCOMPARE(after.size(), before.size());
        for (int i = 0; i < after.size(); ++i) {
            QCOMPARE(after[i]["shape"], before[i]["shape"]);
            QCOMPARE(after[i]["taps"], before[i]["taps"]);
            QCOMPARE(after[i]["reason"], before[i]["reason"]);
        }
    }

    void replayWithOtherSettingsSaysWhereItLeft() {
        // Another smoothing on the same recording: a trial that decides otherwise leaves the
        // recording at that tap, says what both perceived and decided there, and keeps its taps.
        const QString other =
            write("smoother.json", QString(R"({"extends": "%1",
            "classifier": {"bins": 100, "smoothing": 0.1}})")
                                       .arg(sourceFile("experiments/paper.json")));
        const QString out = dir_.filePath("replay_other");
        const Outcome o =
            runCli({"replay", other, dir_.filePath("paper"), "--out", out, "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        int left = 0;
        for (const auto& v : readJson(out + "/summary.json")["following"].toArray()) {
            const QJsonObject t = v.toObject();
            if (t["reason"].toString() != "left the recording") continue;
            ++left;
            QVERIFY(!t["completed"].toBool());
            QVERIFY(t["taps"].toInt() < t["recorded_taps"].toInt());
            const QString detail = t["detail"].toString();
            QVERIFY2(detail.contains("the replay asked for it at") &&
                         detail.contains(QString("they parted at tap %1: the recording read ")
                                             .arg(t["taps"].toInt() - 1)),
                     qPrintable(detail));
        }
        QVERIFY2(left > 0, qPrintable(o.out));
    }

    void replayRefusesWhatItCannotReplay() {
        const QString run = dir_.filePath("paper");
        const QString out = dir_.filePath("refused_replay");
        // A trial the recording does not hold.
        const Outcome missing = runCli(
            {"replay", sourceFile("experiments/polygons.json"), run, "--out", out, "--no-figures"});
        QCOMPARE(missing.exitCode, 2);
        QVERIFY2(missing.err.contains("the recording holds no active") &&
                     missing.err.contains("replay it with the experiment the run was made with"),
                 qPrintable(missing.err));
        // A file where the run's folder belongs.
        const Outcome file = runCli(
            {"replay", sourceFile("experiments/paper.json"), run + "/data/taps.csv", "--out", out});
        QCOMPARE(file.exitCode, 2);
        QVERIFY2(file.err.contains("not a folder"), qPrintable(file.err));
        // A run that followed no contour.
        const QString trainingOnly = dir_.filePath("training_only");
        QVERIFY(QDir().mkpath(trainingOnly + "/data"));
        QVERIFY(QFile::copy(run + "/data/taps.csv", trainingOnly + "/data/taps.csv"));
        const Outcome none =
            runCli({"replay", sourceFile("experiments/paper.json"), trainingOnly, "--out", out});
        QCOMPARE(none.exitCode, 2);
        QVERIFY2(none.err.contains("nothing to replay") && none.err.contains("analyse"),
                 qPrintable(none.err));
        QVERIFY(!QFile::exists(out));  // nothing written
        const Outcome usage = runCli({"replay", sourceFile("experiments/paper.json")});
        QCOMPARE(usage.exitCode, 2);
        QVERIFY2(usage.err.contains("needs a run's folder"), qPrintable(usage.err));
    }
};

QTEST_GUILESS_MAIN(TestCliRecordings)
#include "test_cli_recordings.moc"
