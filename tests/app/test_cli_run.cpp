// A run from the command line writes complete artefacts; a seed makes runs reproducible and
// distinct; a killed run or one that cannot write keeps every finished tap; a folder holding a run
// is replaced only when asked; usage errors exit 2.
#include "CliFixture.h"

class TestCliRun : public CliFixture {
    Q_OBJECT

private slots:
    void paperRunWritesSummaryDataAndFigures() {
        const QString out = dir_.filePath("paper");
        const Outcome o = runCli({"run", sourceFile("experiments/paper.json"), "--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QFile f(out + "/summary.json");
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject s = QJsonDocument::fromJson(f.readAll()).object();
        const QJsonObject v = s["validation"].toObject();
        for (const char* key :
             {"angle_error_deg_mean", "position_error_mm_mean", "valid_range_mm", "by_class"})
            QVERIFY2(v.contains(key), key);
        QCOMPARE(v["by_class"].toArray().size(), 72);
        QCOMPARE(v["valid_range_mm"].toArray().size(), 2);
        QVERIFY(v["valid_range_mm"].toArray()[0].toDouble() <
                v["valid_range_mm"].toArray()[1].toDouble());
        // The paper's shapes face the trained orientations: nothing to caution about.
        QVERIFY(s["cautions"].isArray() && s["cautions"].toArray().isEmpty());
        // Following: passive on the rectangle x 2, active on four shapes x 2, every trial reported.
        const QJsonArray following = s["following"].toArray();
        QCOMPARE(following.size(), 10);
        int followingTaps = 0, passive = 0;
        for (const auto& v : following) {
            const QJsonObject f = v.toObject();
            for (const char* key :
                 {"shape", "mode", "trial", "completed", "reason", "taps", "robot_time_s",
                  "coverage", "mean_contour_distance_mm", "max_contour_distance_mm"})
                QVERIFY2(f.contains(key), key);
            followingTaps += f["taps"].toInt();
            passive += f["mode"].toString() == "passive";
        }
        QCOMPARE(passive, 2);
        const QJsonObject recognition = s["recognition"].toObject();
        QVERIFY(recognition.contains("accuracy") && recognition.contains("accuracy_smoothed"));
        const QJsonArray recognised = recognition["trials"].toArray();
        QCOMPARE(recognised.size(), 8);
        // The confusion of each rule counts every recognised trial under its shape and name.
        QMap<QString, QMap<QString, int>> confusion, confusionSmoothed;
        for (const auto& v : recognised) {
            const QJsonObject r = v.toObject();
            QCOMPARE(r["distances"].toObject().size(), 4);  // the full table of distances
            QVERIFY(r.contains("predicted") && r.contains("predicted_smoothed"));
            ++confusion[r["shape"].toString()][r["predicted"].toString()];
            ++confusionSmoothed[r["shape"].toString()][r["predicted_smoothed"].toString()];
        }
        for (const auto& [key, expected] : {std::pair{"confusion", confusion},
                                            std::pair{"confusion_smoothed", confusionSmoothed}}) {
            const QJsonObject table = recognition[key].toObject();
            QCOMPARE(table.size(), expected.size());
            for (auto row = expected.begin(); row != expected.end(); ++row)
                for (auto cell = row->begin(); cell != row->end(); ++cell)
                    QCOMPARE(table[row.key()].toObject()[cell.key()].toInt(), cell.value());
        }
        const QJsonObject t = s["timing"].toObject();
        QVERIFY(t["wall_s"].toDouble() > 0);
        QCOMPARE(t["taps_simulated"].toInt(), 360 + followingTaps);
        for (const char* table :
             {"taps.csv", "class_regions.csv", "validation_by_class.csv",
              "validation_by_position.csv", "confusion.csv", "test_percepts.csv",
              "following_taps.csv", "following_paths.csv", "following_trials.csv", "outlines.csv",
              "recognition.csv", "path_histograms.csv"})
            QVERIFY2(QFile::exists(out + "/data/" + table), table);
        // taps.csv: a header plus 50 rows per tap.
        QFile taps(out + "/data/taps.csv");
        QVERIFY(taps.open(QIODevice::ReadOnly));
        QCOMPARE(taps.readAll().count('\n'), 1 + 360 * 50);
        QFile followingRecording(out + "/data/following_taps.csv");
        QVERIFY(followingRecording.open(QIODevice::ReadOnly));
        QCOMPARE(followingRecording.readAll().count('\n'), 1 + followingTaps * 50);
        for (const char* figure : {"figure5_taps", "figure6_errors", "figure7_passive_paths",
                                   "figure8_active_paths", "figure9_recognition"}) {
            QFile png(out + "/figures/" + figure + ".png"),
                pdf(out + "/figures/" + figure + ".pdf"), svg(out + "/figures/" + figure + ".svg");
            QVERIFY(png.open(QIODevice::ReadOnly) && pdf.open(QIODevice::ReadOnly) &&
                    svg.open(QIODevice::ReadOnly));
            QVERIFY(png.read(8) == QByteArray("\x89PNG\r\n\x1a\n", 8));
            QVERIFY(pdf.read(5) == "%PDF-");
            QVERIFY(svg.readAll().contains("<svg"));
        }
    }

    void seedMakesRunsReproducibleAndDistinct() {
        const QString a = dir_.filePath("a"), b = dir_.filePath("b"), c = dir_.filePath("c");
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--out", a, "--seed", "5",
                         "--no-figures"})
                     .exitCode,
                 0);
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--out", b, "--seed", "5",
                         "--no-figures"})
                     .exitCode,
                 0);
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--out", c, "--seed", "6",
                         "--no-figures"})
                     .exitCode,
                 0);
        auto read = [](const QString& d) {
            QFile f(d + "/data/taps.csv");
            f.open(QIODevice::ReadOnly);
            return f.readAll();
        };
        QVERIFY(read(a) == read(b));
        QVERIFY(read(a) != read(c));
        QVERIFY(!QDir(a + "/figures").exists());
    }

    void killedRunKeepsEveryFinishedTap() {
        // A long run (many trials) killed part-way: the recording holds whole taps, in order,
        // except at most the one in flight.
        const QString paperScene =
            "\"" + sourceFile("experiments/scenes/paper_rectangle.json") + "\"";
        const QString path =
            write("long.json", QString(R"({"name": "long", "scene": %1, "following": {"trials": [
            {"mode": "active", "object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150]}, "repeats": 400}]}})")
                                   .arg(paperScene));
        const QString out = dir_.filePath("killed");
        QProcess p;
        p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"),
                {"run", path, "--out", out, "--no-figures"});
        QVERIFY(p.waitForStarted());
        QFile recording(out + "/data/following_taps.csv");
        QTRY_VERIFY_WITH_TIMEOUT(recording.exists() && recording.size() > 2000000, 60000);
        p.kill();
        p.waitForFinished();
        QVERIFY(!QFile::exists(out + "/summary.json"));
        QVERIFY(recording.open(QIODevice::ReadOnly));
        const QList<QByteArray> lines = recording.readAll().split('\n');
        const int columns = lines.front().count(',') + 1;
        QCOMPARE(columns, 32);
        int complete = 0, rows = 0;
        QByteArray currentTap;
        for (int i = 1; i < lines.size(); ++i) {
            const QByteArray& line = lines[i];
            if (line.isEmpty()) continue;
            if (line.count(',') + 1 != columns) {
                QCOMPARE(i, lines.size() - 1);  // only the very last line may be cut off
                break;
            }
            const QList<QByteArray> f = line.split(',');
            const QByteArray tap = f[2] + "/" + f[3];
            if (tap != currentTap) {
                if (!currentTap.isEmpty()) QCOMPARE(rows, 50);
                currentTap = tap;
                rows = 0;
                ++complete;
            }
            QCOMPARE(f[19].toInt(), rows);  // samples 0..49 in order
            ++rows;
        }
        QVERIFY(complete > 100);
        // The workbench's own check reads the same: every finished tap whole, the cut reported.
        const Outcome checked = runCli({"check", recording.fileName()});
        QCOMPARE(checked.exitCode, 0);
        QVERIFY2(checked.out.contains(QString("ok (%1 taps").arg(complete)) ||
                     checked.out.contains(QString("ok (%1 taps").arg(complete - 1)),
                 qPrintable(checked.out));
    }

    void aRunThatCannotWriteStopsNamingTheFileAndKeepsItsTaps() {
        // Files may grow to 3 MB: the training taps (2.3 MB) fit, the trials' recording fills up
        // part-way, as a disk filling during a run would. The run stops with the file and the
        // reason, claims no result, and every tap recorded before stays readable.
        const QString out = dir_.filePath("full");
        const Outcome o =
            runCli({"run", sourceFile("experiments/paper.json"), "--out", out, "--no-figures"},
                   [] { test::limitFileSize(3000000); });
        QCOMPARE(o.exitCode, 1);
        QVERIFY2(o.err.contains("run failed: " + out +
                                "/data/following_taps.csv: cannot write the file (File too large)"),
                 qPrintable(o.err));
        QVERIFY2(o.err.contains("Every tap taken so far is in " + out + "/data."),
                 qPrintable(o.err));
        QVERIFY(!QFile::exists(out + "/summary.json"));
        const Outcome taps = runCli({"check", out + "/data/taps.csv"});
        QCOMPARE(taps.exitCode, 0);
        QVERIFY2(taps.out.contains("360 taps"), qPrintable(taps.out));
        const Outcome following = runCli({"check", out + "/data/following_taps.csv"});
        QCOMPARE(following.exitCode, 0);
        QVERIFY2(following.out.contains("ok (") && following.out.contains("cut"),
                 qPrintable(following.out));
    }

    void aFolderHoldingARunIsReplacedOnlyWhenAsked() {
        // A folder holding an earlier run's files (here a summary.json that is a folder, and a
        // file of the user's): refused without --replace, nothing touched; with it, every file of
        // the old run goes first and the user's file stays.
        const QString out = dir_.filePath("summary_blocked");
        QVERIFY(QDir().mkpath(out + "/summary.json/kept"));
        const QString mine = write("summary_blocked/notes.txt", "mine\n");
        const Outcome refused =
            runCli({"run", sourceFile("experiments/paper.json"), "--out", out, "--no-figures"});
        QCOMPARE(refused.exitCode, 2);
        QVERIFY2(refused.err.contains(out + ": this folder already holds a run") &&
                     refused.err.contains("--replace"),
                 qPrintable(refused.err));
        QVERIFY(QFile::exists(out + "/summary.json/kept"));
        QVERIFY(!QFile::exists(out + "/run.json"));
        const Outcome o = runCli({"run", sourceFile("experiments/paper.json"), "--out", out,
                                  "--no-figures", "--replace"});
        QCOMPARE(o.exitCode, 0);
        QVERIFY(QFileInfo(out + "/summary.json").isFile());
        QVERIFY(QFile::exists(mine));
        const Outcome taps = runCli({"check", out + "/data/taps.csv"});
        QCOMPARE(taps.exitCode, 0);
        QVERIFY2(taps.out.contains("360 taps"), qPrintable(taps.out));
    }

    void optionsTakeTheirValueEitherWay() {
        // "--opt value" and "--opt=value" are the same; what does not fit is named.
        const QString out = dir_.filePath("equals");
        const Outcome run = runCli({"run", sourceFile("experiments/paper.json"), "--seed=3",
                                    "--out=" + out, "--no-figures"});
        QCOMPARE(run.exitCode, 0);
        QCOMPARE(readJson(out + "/summary.json")["seed"].toInt(), 3);
        const Outcome unknown = runCli({"run", sourceFile("experiments/paper.json"), "--sed", "3"});
        QCOMPARE(unknown.exitCode, 2);
        QVERIFY2(unknown.err.contains("unknown option '--sed'"), qPrintable(unknown.err));
        const Outcome noValue = runCli({"seeds", sourceFile("experiments/paper.json"), "--to"});
        QCOMPARE(noValue.exitCode, 2);
        QVERIFY2(noValue.err.contains("--to needs a whole number"), qPrintable(noValue.err));
        const Outcome extra = runCli({"check", sourceFile("experiments/paper.json"), "more"});
        QCOMPARE(extra.exitCode, 2);
        QVERIFY2(extra.err.contains("check takes exactly one file"), qPrintable(extra.err));
    }

    void usageErrors() {
        QCOMPARE(runCli({}).exitCode, 2);
        QCOMPARE(runCli({"fly"}).exitCode, 2);
        QCOMPARE(runCli({"run"}).exitCode, 2);
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--seed", "minus"}).exitCode,
                 2);
        const Outcome noRecording = runCli({"analyse", sourceFile("experiments/paper.json")});
        QCOMPARE(noRecording.exitCode, 2);
        QVERIFY2(noRecording.err.contains("needs a recording"), qPrintable(noRecording.err));
        const Outcome help = runCli({"--help"});
        QCOMPARE(help.exitCode, 0);
        QVERIFY(help.out.contains("run <experiment.json>"));
        // Every command's own help, whatever else is given with it.
        for (const char* command : {"run", "seeds", "merge", "compare", "analyse", "replay",
                                    "import", "dump", "calibrate", "check"}) {
            const Outcome own = runCli({command, "--help"});
            QCOMPARE(own.exitCode, 0);
            QVERIFY2(own.out.contains(QString("activetouch-cli ") + command + " <") ||
                         own.out.contains(QString("activetouch-cli ") + command + " "),
                     qPrintable(own.out));
            QVERIFY2(!own.out.contains("activetouch-cli dump") || QString(command) == "dump",
                     "another command's help");
        }
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "-h"}).exitCode, 0);
        // An option given an empty value names nothing: refused, never read as not given.
        const Outcome emptyShard =
            runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "1", "--to", "3",
                    "--shard", "", "--out", dir_.filePath("never")});
        QCOMPARE(emptyShard.exitCode, 2);
        QVERIFY2(emptyShard.err.contains("--shard was given an empty value"),
                 qPrintable(emptyShard.err));
        QVERIFY(!QFile::exists(dir_.filePath("never")));
        const Outcome emptyRig = runCli({"run", sourceFile("experiments/paper.json"), "--rig", "",
                                         "--out", dir_.filePath("never")});
        QCOMPARE(emptyRig.exitCode, 2);
        QVERIFY2(emptyRig.err.contains("--rig was given an empty value"), qPrintable(emptyRig.err));
        const Outcome version = runCli({"--version"});
        QCOMPARE(version.exitCode, 0);
        QVERIFY2(QRegularExpression("^activetouch-cli \\d+\\.\\d+\\.\\d+\n$")
                     .match(version.out)
                     .hasMatch(),
                 qPrintable(version.out));
    }
};

QTEST_GUILESS_MAIN(TestCliRun)
#include "test_cli_run.moc"
