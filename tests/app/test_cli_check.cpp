// check accepts every shipped file, cautions about untrained edges and reads recordings; bad
// input exits 2 with a message naming the file, the place and the problem, and writes nothing.
#include <QRegularExpression>

#include "CliFixture.h"

class TestCliCheck : public CliFixture {
    Q_OBJECT

private slots:
    void checkAcceptsEveryShippedFile() {
        QDir experiments(sourceFile("experiments"));
        QStringList files;
        for (const QString& f : experiments.entryList({"*.json"}, QDir::Files))
            files << experiments.filePath(f);
        QDir scenes(sourceFile("experiments/scenes"));
        for (const QString& f : scenes.entryList({"*.json"}, QDir::Files))
            files << scenes.filePath(f);
        QVERIFY(files.size() >= 2);
        for (const QString& f : files) {
            const Outcome o = runCli({"check", f});
            QVERIFY2(o.exitCode == 0, qPrintable(f + ": " + o.err));
            // Curves face no trained orientation: that file is run knowingly, and cautioned about
            // trial by trial; every other shipped file follows edges its classes face.
            const int untrained = int(o.err.count(" edges face more than "));
            QCOMPARE(untrained, f.endsWith("/experiments/curves.json") ? 3 : 0);
            // Sharp tips (triangle, star, heart, teardrop) and the smallest squares and crosses
            // have parts the fingertip's patch cannot resolve; the paper's shapes have none.
            const int unresolved = int(o.err.count("the fingertip cannot resolve"));
            const bool hasTips = QRegularExpression("/(feature_size|freeform_shapes|general_shapes|"
                                                    "lab_objects)\\.json$")
                                     .match(f)
                                     .hasMatch();
            QVERIFY2(hasTips == (unresolved > 0), qPrintable(f + ": " + o.err));
            QCOMPARE(int(o.err.count("caution:")), untrained + unresolved);
        }
    }

    void checkCautionsAboutEdgesNoTrainedOrientationFaces() {
        // The run is allowed (docs/results.md measures how following degrades with rotation), but the
        // person is told before any tap which trial and edge, and what would follow it.
        const QString path = write(
            "turned.json",
            QString(
                R"({"extends": "%1", "name": "turned", "following": {"trials": [{"mode": "active", "object": {"shape": "rectangle", "rotation_deg": 20, "offset_mm": [150, 150]}}]}})")
                .arg(sourceFile("experiments/paper.json")));
        const Outcome o = runCli({"check", path});
        QCOMPARE(o.exitCode, 0);
        QVERIFY2(o.out.contains("ok"), qPrintable(o.out));
        QVERIFY2(o.err.startsWith("caution: /following/trials/0 (rectangle): 4 of 4 edges face"),
                 qPrintable(o.err));
        QVERIFY2(o.err.contains("20 deg off"), qPrintable(o.err));
        QVERIFY2(o.err.contains("classes/orientations_deg"), qPrintable(o.err));
    }

    void checkCautionsAboutFeaturesNarrowerThanTheFingertip() {
        // A comb whose teeth and gaps are 2 mm wide, on a block as wide as the paper's
        // rectangle: check says which trial, how much of it and where, before any tap.
        const QString path = write(
            "comb.json",
            QString(
                R"({"extends": "%1", "name": "comb", "following": {"trials": [{"mode": "active", "label": "comb", "object": {"shape": "polygon", "polygon_mm": [[-24,-29],[24,-29],[24,25],[5,25],[5,31],[3,31],[3,25],[1,25],[1,31],[-1,31],[-1,25],[-3,25],[-3,31],[-5,31],[-5,25],[-24,25]], "offset_mm": [150, 150]}}, {"mode": "active", "object": {"shape": "rectangle", "offset_mm": [150, 150]}}]}})")
                .arg(sourceFile("experiments/paper.json")));
        const Outcome o = runCli({"check", path});
        QCOMPARE(o.exitCode, 0);
        QCOMPARE(int(o.err.count("caution:")), 1);
        QVERIFY2(o.err.startsWith("caution: /following/trials/0 (comb): "), qPrintable(o.err));
        QVERIFY2(o.err.contains("cannot resolve") && o.err.contains("a tooth, spike or outside corner at (") &&
                     o.err.contains("a notch, gap or inside corner at (") &&
                     o.err.contains("coverage counts only the"),
                 qPrintable(o.err));
    }

    void badInputExitsTwoAndWritesNothing_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("message");
        const QString scene =
            R"({"object": {"shape": "rectangle", "offset_mm": [150, 150]}, "effects": [EFFECTS]})";
        auto experiment = [&](const QString& effects) {
            QString s = scene;
            s.replace("EFFECTS", effects);
            return QString(R"({"name": "bad", "scene": %1})").arg(s);
        };
        QTest::newRow("malformed JSON") << "broken.json"
                                        << R"({"name": "x", "scene": {)"
                                        << "line 1, column";
        QTest::newRow("unknown effect") << "effect.json" << experiment(R"({"name": "magic"})")
                                        << "/scene/effects/0/name: unknown effect 'magic'";
        QTest::newRow("missing parameter")
            << "param.json" << experiment(R"({"name": "taxel_noise"})")
            << "missing required number 'sigma_counts'";
        QTest::newRow("out-of-range parameter")
            << "range.json" << experiment(R"({"name": "stage_error", "sigma_mm": 9})")
            << "/scene/effects/0/sigma_mm";
        QTest::newRow("self-intersecting polygon")
            << "bowtie.json"
            << R"({"name": "x", "scene": {"object": {"shape": "polygon", "polygon_mm": [[0,0],[40,40],[40,0],[0,40]], "offset_mm": [150, 150]}}})"
            << "/scene/object/polygon_mm: the polygon is not a usable outline: the outline "
               "intersects itself";
        QTest::newRow("degenerate polygon")
            << "line.json"
            << R"({"name": "x", "scene": {"object": {"shape": "polygon", "polygon_mm": [[0,0],[10,0],[20,0]], "offset_mm": [150, 150]}}})"
            << "encloses no area";
        QTest::newRow("unknown shape") << "shape.json"
                                       << R"({"name": "x", "scene": {"object": {"shape": "blob"}}})"
                                       << "unknown shape 'blob'";
        QTest::newRow("a scene is not an experiment") << "scene.json"
                                                      << R"({"object": {"shape": "rectangle"}})"
                                                      << "not an experiment file";
        const QString paperScene =
            "\"" + sourceFile("experiments/scenes/paper_rectangle.json") + "\"";
        QTest::newRow("start pose off the object")
            << "start.json"
            << QString(
                   R"({"name": "x", "scene": %1, "following": {"trials": [{"object": {"shape": "l", "offset_mm": [150, 150]}, "start_mm": [150, 100]}]}})")
                   .arg(paperScene)
            << "/following/trials/0/start_mm: the start pose (150.00, 100.00) mm is 20.0 mm "
               "outside the object";
        QTest::newRow("object larger than the stage travel")
            << "big.json"
            << QString(
                   R"({"name": "x", "scene": %1, "following": {"trials": [{"object": {"shape": "rectangle", "width_mm": 700, "height_mm": 50, "offset_mm": [350, 150]}}]}})")
                   .arg(paperScene)
            << "/following/trials/0/object: the object (x 0..700, y 125..175 mm) does not fit "
               "inside the stage travel (0..650, 0..300 mm)";
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

    void checkReadsTapRecordings() {
        const QString out = dir_.filePath("csvrun");
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--out", out, "--no-figures"})
                     .exitCode,
                 0);
        const Outcome good = runCli({"check", out + "/data/taps.csv"});
        QCOMPARE(good.exitCode, 0);
        QVERIFY(good.out.contains("360 taps"));
        const QString bad = write("bad_taps.csv", "set,class,orientation_deg\n1,2,3\n");
        const Outcome o = runCli({"check", bad});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(
            o.err.contains(bad) && o.err.contains("line 1") && o.err.contains("unexpected columns"),
            qPrintable(o.err));
        const QString nan = write("nan_taps.csv",
                                  "set,class,orientation_deg,position,true_offset_mm,pose_x_mm,"
                                  "pose_y_mm,robot_time_s,ending,sample,"
                                  "taxel_0,taxel_1,taxel_2,taxel_3,taxel_4,taxel_5,taxel_6,taxel_7,"
                                  "taxel_8,taxel_9,taxel_10,taxel_11\n"
                                  "1,0,270,1,-8.5,150,129,0,reflex,0,nan,0,0,0,0,0,0,0,0,0,0,0\n");
        const Outcome n = runCli({"check", nan});
        QCOMPARE(n.exitCode, 2);
        QVERIFY2(n.err.contains("line 2, column taxel_0"), qPrintable(n.err));
        const QString over = write("over_taps.csv",
                                   "set,class,orientation_deg,position,true_offset_mm,pose_x_mm,"
                                   "pose_y_mm,robot_time_s,ending,sample,"
                                   "taxel_0,taxel_1,taxel_2,taxel_3,taxel_4,taxel_5,taxel_6,taxel_"
                                   "7,taxel_8,taxel_9,taxel_10,taxel_11\n"
                                   "1,0,270,1,-8.5,150,129,0,reflex,0,0,0,0,300,0,0,0,0,0,0,0,0\n");
        const Outcome v = runCli({"check", over});
        QCOMPARE(v.exitCode, 2);
        QVERIFY2(
            v.err.contains("column taxel_3") && v.err.contains("outside the fingertip's 0..255"),
            qPrintable(v.err));
    }

    void aRecordingWithoutItsRunIsHeldToAFingertipAndToDataSetsFromOne() {
        // Without a run.json beside it, a recording is held to the paper's fingertip (or to the
        // experiment given): 11 or 13 taxels, or a data set below 1, are refused as analyse
        // refuses them.
        auto row = [](int taxels, int set) {
            QString header = "set,class,orientation_deg,position,true_offset_mm,pose_x_mm,"
                             "pose_y_mm,robot_time_s,ending,stop_depth_mm,sample";
            QString values = QString("%1,0,270,1,-8.5,150,129,0,reflex,0,0").arg(set);
            for (int k = 0; k < taxels; ++k) {
                header += QString(",taxel_%1").arg(k);
                values += ",0";
            }
            return header + "\n" + values + "\n";
        };
        for (const int taxels : {11, 13}) {
            const QString file = write(QString("taxels_%1.csv").arg(taxels), row(taxels, 1));
            const Outcome o = runCli({"check", file});
            QCOMPARE(o.exitCode, 2);
            QVERIFY2(o.err.contains(file) &&
                         o.err.contains(QString("has %1 taxel columns").arg(taxels)) &&
                         o.err.contains("has 12 taxels"),
                     qPrintable(o.err));
        }
        const QString minus = write("set_minus.csv", row(12, -7));
        const Outcome o = runCli({"check", minus});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains("column set") && o.err.contains("data set -7 is below 1"),
                 qPrintable(o.err));
        QCOMPARE(runCli({"check", write("good.csv", row(12, 1))}).exitCode, 0);
        // Checked against an experiment with another fingertip, its count is the one held to.
        const Outcome against = runCli({"check", write("with.csv", row(12, 1)), "--experiment",
                                        sourceFile("experiments/paper.json")});
        QVERIFY2(against.exitCode == 0, qPrintable(against.err));
    }
};

QTEST_GUILESS_MAIN(TestCliCheck)
#include "test_cli_check.moc"
