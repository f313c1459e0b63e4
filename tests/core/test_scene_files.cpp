// Scene and experiment files: every mistake a user can make is named with the file, the place
// and what to do.
#include <QTemporaryDir>
#include <QtTest>
#include <fstream>
#include <functional>

#include "core/experiment/Experiment.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "support/Paths.h"

using namespace activetouch;

namespace {
const char* kGoodScene = R"({
  "object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150], "top_height_mm": 10},
  "fingertip": "icub_fingertip_2010",
  "tap": {"retract_height_mm": 12, "descent_speed_mm_s": 25, "stroke_mm": 5, "contact_threshold_counts": 250},
  "effects": [{"name": "taxel_noise", "sigma_counts": 1.5}]
})";
}  // namespace

/// `read` refuses its file with an InputError that starts with `path` and names `place` and
/// `problem`.
void expectRefusal(const std::function<void()>& read, const QString& path, const QString& place,
                   const QString& problem) {
    try {
        read();
        QFAIL("the file was accepted");
    } catch (const InputError& e) {
        const QString message = e.what();
        QVERIFY2(message.startsWith(path), qPrintable(message));
        QVERIFY2(message.contains(place), qPrintable(message));
        QVERIFY2(message.contains(problem), qPrintable(message));
    }
}

class TestSceneFiles : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

    std::string write(const QString& name, const std::string& text) {
        const std::string path = dir_.filePath(name).toStdString();
        std::ofstream(path) << text;
        return path;
    }

private slots:
    void goodSceneLoads() {
        const SceneSpec s = loadScene(write("good.json", kGoodScene));
        QCOMPARE(s.object.outline().area(), 48.0 * 58.0);
        QCOMPARE(int(s.effects.size()), 1);
        QCOMPARE(s.fingertip.taxels.size(), std::size_t(12));
        QCOMPARE(s.strokeLimitDepth(), 3.0);
        // What is written back reads back the same.
        const SceneSpec again =
            parseScene(sceneToJson(s), "round trip", "", dir_.path().toStdString());
        QCOMPARE(sceneToJson(again).dump(), sceneToJson(s).dump());
    }

    void aLongStringIsShownCutWithoutBreakingACharacter() {
        // A document that is one long string: refused, quoting its start, even where the cut
        // for the message falls inside a character of two bytes.
        const std::string text = "\"" + std::string(59, 'a') + "\xc3\xbb" + std::string(100, 'b') + "\"";
        try {
            loadScene(write("cut.json", text));
            QFAIL("a string was taken for a scene");
        } catch (const InputError& e) {
            QVERIFY2(QString::fromUtf8(e.what()).contains("expected a JSON object"), e.what());
        }
    }

    void shippedExperimentsAndScenesLoad() {
        const SceneSpec s = loadScene(test::sourcePath("experiments/scenes/paper_rectangle.json"));
        QVERIFY(s.lists("taxel_noise"));
        const ExperimentSpec e = loadExperiment(test::sourcePath("experiments/paper.json"));
        QCOMPARE(e.name, std::string("paper"));
        QCOMPARE(e.classes.classCount(), 72);
        QCOMPARE(e.classifier.bins, 100);
    }

    void anExperimentExtendsAnotherWithOnlyWhatDiffers() {
        write("good.json", kGoodScene);
        QDir(dir_.path()).mkdir("variants");
        write("base.json", R"({"name": "base", "scene": "good.json", "seed": 4,
            "classifier": {"bins": 60, "smoothing": 0.05},
            "training": {"data_sets": 3, "training_sets": [1]},
            "following": {"follow_step_mm": 3, "trials": [
                {"mode": "active", "object": {"shape": "rectangle", "offset_mm": [150, 150]}}]}})");
        // In another folder: the base and the scene are still found relative to their own files.
        const std::string path = write("variants/finer.json", R"({"extends": "../base.json",
            "name": "finer", "classifier": {"bins": 120},
            "training": {"training_sets": [1, 2]}, "following": {"trials": null}})");
        const ExperimentSpec e = loadExperiment(path);
        QCOMPARE(e.name, std::string("finer"));
        QCOMPARE(e.classifier.bins, 120);                  // replaced
        QCOMPARE(e.classifier.smoothing, 0.05);            // kept from the base
        QCOMPARE(int(e.scene.seed), 4);                    // kept from the base
        QCOMPARE(e.training.dataSets, 3);                  // objects merge key by key
        QCOMPARE(int(e.training.trainingSets.size()), 2);  // lists replace
        QCOMPARE(e.following.followStep_mm, 3.0);
        QVERIFY(e.trials.empty());  // null removes
        QCOMPARE(e.scene.object.outline().area(), 48.0 * 58.0);

        const ExperimentSpec shipped =
            loadExperiment(test::sourcePath("experiments/paper_sequential.json"));
        const ExperimentSpec paper = loadExperiment(test::sourcePath("experiments/paper.json"));
        QCOMPARE(shipped.following.beliefThreshold, 0.99999999);
        QCOMPARE(shipped.trials.size(), paper.trials.size());
        QCOMPARE(shipped.scene.effects.size(), paper.scene.effects.size());
        QCOMPARE(paper.classifier.kernelSigma_bins, 0.0);  // the paper's histogram

        const ExperimentSpec kernel =
            loadExperiment(test::sourcePath("experiments/paper_kernel.json"));
        QCOMPARE(kernel.classifier.kernelSigma_bins, 2.5);
        QCOMPARE(kernel.classifier.bins, paper.classifier.bins);
        QCOMPARE(kernel.classifier.smoothing, paper.classifier.smoothing);
        QCOMPARE(kernel.trials.size(), paper.trials.size());

        QVERIFY(!paper.training.retrainOnAllSets);  // the paper follows with set 1's classifier
        const ExperimentSpec retrained =
            loadExperiment(test::sourcePath("experiments/paper_retrained.json"));
        QVERIFY(retrained.training.retrainOnAllSets);
        QCOMPARE(retrained.training.trainingSets, paper.training.trainingSets);
        QCOMPARE(retrained.training.dataSets, paper.training.dataSets);
        QCOMPARE(retrained.training.tapsPerClass, paper.training.tapsPerClass);
        QCOMPARE(retrained.classifier.kernelSigma_bins, paper.classifier.kernelSigma_bins);
        QCOMPARE(retrained.trials.size(), paper.trials.size());
    }

    void libraryShapesAreNamedInAnyCaseAndShownAsThePaperNamesThem() {
        // "c" and "C" are the same shape; figures, tables and files name it "C", as the paper.
        write("good.json", kGoodScene);
        const std::string path = write("cases.json", R"({"name": "cases", "scene": "good.json",
            "following": {"trials": [
                {"object": {"shape": "c", "offset_mm": [150, 150]}},
                {"object": {"shape": "L", "offset_mm": [150, 150]}},
                {"object": {"shape": "Cross", "offset_mm": [150, 150]}}]}})");
        const ExperimentSpec e = loadExperiment(path);
        QCOMPARE(int(e.trials.size()), 3);
        QCOMPARE(e.trials[0].object.shape, std::string("C"));
        QCOMPARE(e.trials[0].label, std::string("C"));
        QCOMPARE(e.trials[1].object.shape, std::string("L"));
        QCOMPARE(e.trials[2].object.shape, std::string("cross"));
        QCOMPARE(e.trials[0].object.outline().area(),
                 libraryShape("C", defaultShapeSize("C")).area());
        std::string scene = kGoodScene;
        scene.replace(scene.find("\"rectangle\""), 11, "\"l\"");
        const SceneSpec s = loadScene(write("l.json", scene));
        QCOMPARE(sceneToJson(s)["object"]["shape"].get<std::string>(), std::string("L"));
    }

    void oneDimensionScalesALibraryShapeWholeAndBothSetEach() {
        // A lab gives the size it measured: one dimension keeps the shape's aspect (its arms and
        // opening too); both dimensions set each; an arm given is kept.
        auto object = [](const char* json) {
            return parseObject(JsonFields(Json::parse(json), "test", "/object"));
        };
        const ShapeSize ellipse = defaultShapeSize("ellipse");
        const ObjectSpec wide = object(R"({"shape": "ellipse", "width_mm": 144})");
        QCOMPARE(wide.size.width, 144.0);
        QCOMPARE(wide.size.height, 2.0 * ellipse.height);
        const ObjectSpec tall = object(R"({"shape": "C", "height_mm": 90})");
        QCOMPARE(tall.size.width, 90.0);
        QCOMPARE(tall.size.arm, 1.5 * defaultShapeSize("C").arm);
        QCOMPARE(tall.size.opening, 1.5 * defaultShapeSize("C").opening);
        const ObjectSpec armed = object(R"({"shape": "cross", "width_mm": 120, "arm_mm": 25})");
        QCOMPARE(armed.size.height, 120.0);
        QCOMPARE(armed.size.arm, 25.0);
        const ObjectSpec both = object(R"({"shape": "ellipse", "width_mm": 100, "height_mm": 30})");
        QCOMPARE(both.size.width, 100.0);
        QCOMPARE(both.size.height, 30.0);
        // The outline the scaled size draws is the default's, scaled: twice the area over 1.4142.
        const double area = libraryShape("ellipse", ellipse).area();
        QVERIFY(std::abs(object(R"({"shape": "ellipse", "width_mm": 101.82337649086285})")
                             .outline()
                             .area() -
                         2.0 * area) < 1e-6 * area);
    }

    void anObjectDrawnAsSvgPathData() {
        // A triangle drawn in SVG's frame (y down, apex at the top): centred on its bounding box,
        // the right way up, placed at the offset; its curves flattened within the tolerance.
        write("good.json", kGoodScene);
        std::string scene = kGoodScene;
        const std::string from = R"("shape": "rectangle")";
        scene.replace(scene.find(from), from.size(),
                      R"("shape": "svg", "svg_path": "M20 0 L40 30 L0 30 Z")");
        const SceneSpec s = loadScene(write("svg.json", scene));
        QCOMPARE(s.object.shape, std::string("polygon"));
        const Polygon outline = s.object.outline();
        QVERIFY(std::abs(outline.area() - 600.0) < 1e-9);
        // The apex is up (larger y), at the middle of the base.
        double apexY = -1e9, baseY = 1e9;
        for (const Vec2& v : outline.vertices()) {
            apexY = std::max(apexY, v.y);
            baseY = std::min(baseY, v.y);
        }
        QVERIFY(std::abs(apexY - (s.object.offset.y + 15.0)) < 1e-9);
        QVERIFY(std::abs(baseY - (s.object.offset.y - 15.0)) < 1e-9);
        // A disk of radius 15 from two arcs, at a coarse tolerance: within it of the circle.
        std::string disk = kGoodScene;
        disk.replace(disk.find(from), from.size(),
                     R"("shape": "svg", "svg_tolerance_mm": 0.2,
                        "svg_path": "M0 15 a15 15 0 0 1 30 0 a15 15 0 0 1 -30 0 z")");
        const SceneSpec d = loadScene(write("disk.json", disk));
        const Polygon diskOutline = d.object.outline();
        for (const Vec2& v : diskOutline.vertices())
            QVERIFY(std::abs(std::hypot(v.x - d.object.offset.x, v.y - d.object.offset.y) - 15.0) <=
                    0.2);
        // Bad path data is refused at its character.
        std::string bad = kGoodScene;
        bad.replace(bad.find(from), from.size(), R"("shape": "svg", "svg_path": "M0 0 L10 0 K")");
        const std::string path = write("bad_svg.json", bad);
        expectRefusal([&] { loadScene(path); }, QString::fromStdString(path),
                      "/object/svg_path, character 12", "unknown command 'K'");
        std::string none = kGoodScene;
        none.replace(none.find(from), from.size(), R"("shape": "svg")");
        const std::string nonePath = write("no_svg.json", none);
        expectRefusal([&] { loadScene(nonePath); }, QString::fromStdString(nonePath),
                      "/object/svg_path", "needs 'svg_path'");
    }

    void generalShapesOrientationStepsAndDrawnTurns() {
        // Every library shape builds at its default size; a regular polygon has an edge facing
        // each way every 360 / sides degrees, the first straight down; an orientation step lists
        // the orientations round the circle from 270; a drawn turn differs from trial to trial.
        for (const auto& n : libraryShapeNames()) {
            const Polygon p = libraryShape(n, defaultShapeSize(n));
            QVERIFY2(p.area() > 500.0, n.c_str());
        }
        const ObjectSpec poly = parseObject(JsonFields(
            Json::parse(R"({"shape": "regular_polygon", "sides": 36, "across_corners_mm": 230})"),
            "test", "/object"));
        const Polygon outline = poly.outline();
        QCOMPARE(int(outline.size()), 36);
        std::vector<double> normals;
        for (std::size_t e = 0; e < outline.size(); ++e) {
            const Vec2 n = outline.outwardNormal(e);
            normals.push_back(std::fmod(std::atan2(n.y, n.x) * 180 / M_PI + 360.0, 360.0));
        }
        for (int k = 0; k < 36; ++k) {
            const double want = std::fmod(270.0 + 10.0 * k, 360.0);
            QVERIFY(std::any_of(normals.begin(), normals.end(),
                                [&](double a) { return angleDifferenceDeg(a, want) < 1e-6; }));
        }
        write("good.json", kGoodScene);
        const std::string path =
            write("stepped.json",
                  R"({"name": "x", "scene": "good.json", "classes": {"orientation_step_deg": 45},
                "following": {"percept": "continuous", "trials": [
                  {"object": {"shape": "star", "rotation_deg": "random"}, "repeats": 2}]}})");
        // The rectangle has no edge facing 45 degrees: training on it is refused by name.
        try {
            loadExperiment(path);
            QFAIL("an experiment whose training object lacks an orientation was accepted");
        } catch (const InputError& e) {
            QVERIFY2(QString(e.what()).contains("no edge facing"), e.what());
        }
        write("octagon.json",
              QString(kGoodScene)
                  .replace(R"("shape": "rectangle")",
                           R"("shape": "regular_polygon", "sides": 8, "across_corners_mm": 80)")
                  .toStdString());
        const std::string octagon =
            write("stepped8.json",
                  R"({"name": "x", "scene": "octagon.json", "classes": {"orientation_step_deg": 45},
                "following": {"percept": "continuous", "trials": [
                  {"object": {"shape": "star", "rotation_deg": "random"}, "repeats": 2}]}})");
        const ExperimentSpec e = loadExperiment(octagon);
        QCOMPARE(e.classes.orientationsDeg,
                 (std::vector<double>{270, 315, 0, 45, 90, 135, 180, 225}));
        QVERIFY(e.following.percept == PerceptKind::Continuous);
        QVERIFY(e.trials.front().object.rotationDrawn);
        QCOMPARE(objectToJson(e.trials.front().object)["rotation_deg"], Json("random"));
        // The star's edges face between the eight orientations: the discrete percept would snap
        // them, and check says so; the continuous one reads between them, and says nothing.
        QVERIFY(untrainedEdgeCautions(e).empty());
        ExperimentSpec discrete = e;
        discrete.following.percept = PerceptKind::Discrete;
        QVERIFY(!untrainedEdgeCautions(discrete).empty());
    }

    void badSceneNamesFilePlaceAndProblem_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("place");
        QTest::addColumn<QString>("problem");
        const QString good = kGoodScene;
        auto swap = [&](const QString& from, const QString& to) {
            QString s = good;
            s.replace(from, to);
            return s;
        };
        QTest::newRow("malformed JSON")
            << swap("\"width_mm\": 48,", "\"width_mm\": 48,,") << "line 2, column"
            << "not valid JSON";
        QTest::newRow("unknown shape") << swap("\"rectangle\"", "\"hexagon\"") << "/object/shape"
                                       << "unknown shape 'hexagon'";
        QTest::newRow("unknown key") << swap("\"width_mm\"", "\"widht_mm\"") << "/object/widht_mm"
                                     << "unknown key 'widht_mm'";
        QTest::newRow("out of range")
            << swap("\"stroke_mm\": 5", "\"stroke_mm\": -5") << "/tap/stroke_mm"
            << "outside the allowed range";
        QTest::newRow("wrong type")
            << swap("\"width_mm\": 48", "\"width_mm\": \"wide\"") << "/object/width_mm"
            << "expected a number";
        // The number as written and the range in full, not as the wrapped value or 2.1e+09.
        QTest::newRow("seed beyond any whole number")
            << swap("\"fingertip\"", "\"seed\": 18446744073709551615, \"fingertip\"") << "/seed"
            << "'seed' is 18446744073709551615, outside the allowed range (between 0 and "
               "2147483647)";
        QTest::newRow("negative seed")
            << swap("\"fingertip\"", "\"seed\": -3, \"fingertip\"") << "/seed"
            << "'seed' is -3, outside the allowed range";
        QTest::newRow("missing shape") << swap("\"shape\": \"rectangle\",", "") << "/object/shape"
                                       << "missing required text 'shape'";
        QTest::newRow("self-intersecting polygon")
            << swap("\"shape\": \"rectangle\", \"width_mm\": 48, \"height_mm\": 58,",
                    "\"shape\": \"polygon\", \"polygon_mm\": [[0,0],[40,40],[40,0],[0,40]],")
            << "/object/polygon_mm"
            << "intersects itself";
        QTest::newRow("degenerate polygon")
            << swap("\"shape\": \"rectangle\", \"width_mm\": 48, \"height_mm\": 58,",
                    "\"shape\": \"polygon\", \"polygon_mm\": [[0,0],[10,0],[20,0]],")
            << "/object/polygon_mm"
            << "no area";
        QTest::newRow("object off the stage")
            << swap("[150, 150]", "[640, 150]") << "/object"
            << "the object (x 616..664, y 121..179 mm) does not fit inside the stage travel "
               "(0..650, 0..300 mm)";
        // So far off that no outline survives: named at the offset, not inside the geometry.
        QTest::newRow("object a thousand kilometres off")
            << swap("[150, 150]", "[150, 1e9]") << "/object/offset_mm"
            << "placed at (150, 1000000000) mm, the object's outline is not usable: vertex 0 "
               "(126, 1e+09) lies more than 1 km from the origin";
        QTest::newRow("object above retract height")
            << swap("\"top_height_mm\": 10", "\"top_height_mm\": 20") << "/object/top_height_mm"
            << "retract height";
        QTest::newRow("tap does not fit the window")
            << swap("\"descent_speed_mm_s\": 25", "\"descent_speed_mm_s\": 5") << "/tap"
            << "tap window";
        QTest::newRow("unknown fingertip")
            << swap("icub_fingertip_2010", "robot_thumb") << "/fingertip"
            << "fingertip 'robot_thumb' not found";
        QTest::newRow("effects not a list")
            << swap("[{\"name\": \"taxel_noise\", \"sigma_counts\": 1.5}]", "{}") << "/effects"
            << "expected a list";
        QTest::newRow("effect listed twice")
            << swap("{\"name\": \"taxel_noise\", \"sigma_counts\": 1.5}",
                    "{\"name\": \"taxel_noise\", \"sigma_counts\": 1.5}, {\"name\": "
                    "\"taxel_noise\", \"sigma_counts\": 1}")
            << "/effects/1/name"
            << "listed twice";
    }
    void badSceneNamesFilePlaceAndProblem() {
        QFETCH(QString, text);
        QFETCH(QString, place);
        QFETCH(QString, problem);
        const std::string path = write("bad.json", text.toStdString());
        expectRefusal([&] { loadScene(path); }, QString::fromStdString(path), place, problem);
    }

    void polygonFilesInEveryFormPeopleWriteThem() {
        const std::vector<Vec2> square{{0, 0}, {30, 0}, {30, 30}, {0, 30}};
        // A bare list of vertices, an object (its shape may be left out) and a scene all load.
        QCOMPARE(loadPolygonFile(write("list.json", "[[0,0],[30,0],[30,30],[0,30]]")), square);
        QCOMPARE(loadPolygonFile(
                     write("object.json", R"({"polygon_mm": [[0,0],[30,0],[30,30],[0,30]]})")),
                 square);
        QCOMPARE(loadPolygonFile(write("scene.json",
                                       R"({"object": {"shape": "polygon", "polygon_mm":
                                           [[0,0],[30,0],[30,30],[0,30]], "top_height_mm": 8}})")),
                 square);
    }

    void badPolygonFilesNameFilePlaceAndProblem_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("place");
        QTest::addColumn<QString>("problem");
        QTest::newRow("a number") << "42"
                                  << ""
                                  << "expected a list of [x, y] vertices in mm, an object";
        QTest::newRow("text") << "\"square\""
                              << ""
                              << "found \"square\"";
        QTest::newRow("a bad vertex") << "[[0,0],[30,0],[30],[0,30]]"
                                      << "at /2"
                                      << "expected a vertex [x, y] in mm";
        QTest::newRow("two vertices") << "[[0,0],[30,0]]"
                                      << ""
                                      << "not a usable outline";
        QTest::newRow("empty list") << "[]"
                                    << ""
                                    << "not a usable outline";
        QTest::newRow("self-intersecting") << "[[0,0],[40,40],[40,0],[0,40]]"
                                           << ""
                                           << "intersects itself";
        QTest::newRow("all points equal") << "[[5,5],[5,5],[5,5],[5,5]]"
                                          << ""
                                          << "not a usable outline";
        QTest::newRow("scene whose object is a number") << R"({"object": 5})"
                                                        << "at /object"
                                                        << "found 5";
        QTest::newRow("a library shape") << R"({"object": {"shape": "rectangle"}})"
                                         << "at /object/shape"
                                         << "not a polygon; choose it in the shape list";
        QTest::newRow("object without vertices") << R"({"top_height_mm": 8})"
                                                 << "at /polygon_mm"
                                                 << "needs 'polygon_mm'";
    }
    void badPolygonFilesNameFilePlaceAndProblem() {
        QFETCH(QString, text);
        QFETCH(QString, place);
        QFETCH(QString, problem);
        const std::string path = write("bad_polygon.json", text.toStdString());
        expectRefusal([&] { loadPolygonFile(path); }, QString::fromStdString(path), place, problem);
    }

    void missingFileOrFolderIsNamed_data() {
        QTest::addColumn<QString>("path");
        QTest::addColumn<QString>("problem");
        QTest::newRow("missing") << dir_.filePath("nowhere.json") << "no such file; check the path";
        QDir(dir_.path()).mkpath("a_folder.json");
        QTest::newRow("a folder") << dir_.filePath("a_folder.json")
                                  << "this is a folder, not a file";
    }
    void missingFileOrFolderIsNamed() {
        // Every reader of a user's file says which: a scene, a polygon, a tap recording and a
        // following recording.
        QFETCH(QString, path);
        QFETCH(QString, problem);
        const std::string p = path.toStdString();
        const std::vector<std::function<void()>> readers{
            [&] { loadScene(p); }, [&] { loadPolygonFile(p); }, [&] { readTapCsv(p, ClassSet{}); },
            [&] { checkFollowingRecording(p); }};
        for (const auto& read : readers) expectRefusal(read, path, "", problem);
    }

    void badExperimentSettings_data() {
        QTest::addColumn<QString>("experiment");
        QTest::addColumn<QString>("problem");
        const QString head = R"({"name": "x", "scene": "good.json", )";
        QTest::newRow("training set beyond the data sets")
            << head + R"("training": {"data_sets": 3, "training_sets": [4]}})"
            << "does not exist";
        QTest::newRow("training set not a whole number")
            << head + R"("training": {"data_sets": 3, "training_sets": [1.5]}})"
            << "data set 1.5 is not a whole number";
        QTest::newRow("every set trains")
            << head + R"("training": {"data_sets": 2, "training_sets": [1, 2]}})"
            << "leave at least one set to test";
        QTest::newRow("orientation step not dividing the circle")
            << head + R"("classes": {"orientation_step_deg": 7}})"
            << "does not divide the circle";
        QTest::newRow("orientation step beside a list")
            << head + R"("classes": {"orientations_deg": [0, 90], "orientation_step_deg": 10}})"
            << "not both";
        QTest::newRow("unknown percept") << head + R"("following": {"percept": "fuzzy"}})"
                                         << "percept 'fuzzy' is neither discrete";
        QTest::newRow("unknown belief evidence")
            << head + R"("following": {"belief_evidence": "bayes"}})"
            << "belief_evidence 'bayes' is neither calibrated";
        QTest::newRow("belief evidence not text")
            << head + R"("following": {"belief_evidence": 1}})"
            << "belief_evidence";
        QTest::newRow("curvature from one tap") << head + R"("following": {"curvature_taps": 1}})"
                                                << "a turn needs two angles";
        QTest::newRow("negative temperature")
            << head + R"("following": {"percept_temperature": -1}})"
            << "outside the allowed range";
        QTest::newRow("rotation as other text")
            << head +
                   R"("following": {"trials": [{"object": {"shape": "star", "rotation_deg": "any"}}]}})"
            << "or \"random\" for an angle drawn";
        QTest::newRow("a drawn turn that can leave the travel")
            << head +
                   R"("following": {"trials": [{"object": {"shape": "rectangle", "width_mm": 280, "height_mm": 20, "rotation_deg": "random", "offset_mm": [150, 150]}}]}})"
            << "turned any way";
        QTest::newRow("no smoothing") << head + R"("classifier": {"smoothing": 0}})"
                                      << "outside the allowed range";
        QTest::newRow("negative kernel") << head + R"("classifier": {"kernel_sigma_bins": -1}})"
                                         << "'kernel_sigma_bins' is -1, outside the allowed range";
        QTest::newRow("kernel wider than 50 bins")
            << head + R"("classifier": {"kernel_sigma_bins": 51}})"
            << "'kernel_sigma_bins' is 51, outside the allowed range";
        QTest::newRow("kernel as text") << head + R"("classifier": {"kernel_sigma_bins": "wide"}})"
                                        << "kernel_sigma_bins";
        QTest::newRow("retraining as text")
            << head + R"("training": {"retrain_on_all_sets": "yes"}})"
            << "at /training/retrain_on_all_sets: expected true or false, found \"yes\"";
        QTest::newRow("scene file missing") << R"({"name": "x", "scene": "nope.json"})"
                                            << "does not exist";
        QTest::newRow("orientation with no edge")
            << head + R"("classes": {"orientations_deg": [45]}})"
            << "no edge facing";
        QTest::newRow("one orientation twice")
            << head + R"("classes": {"orientations_deg": [270, 0, 90, 180, -90]}})"
            << "orientation -90 deg faces the same way as orientation 270 deg";
        QTest::newRow("plane positions past the object's far side")
            << head + R"("classes": {"positions": 100}})"
            << "at /scene: training on the scene's object: position 1 at the right edge puts the "
               "tip 49.5 mm inside the edge, past the far side of the training object";
        QTest::newRow("air positions beyond the stage travel")
            << R"({"name": "x", "scene": "near_the_travel_end.json"})"
            << "position 10 at the left edge taps at (0.5, 150) mm (+-0.8 mm placement jitter), "
               "outside the stage travel (0..650, 0..300 mm)";
        QTest::newRow("no name") << R"({"scene": "good.json"})"
                                 << "missing required text 'name'";
        QTest::newRow("extends a missing base") << R"({"extends": "nowhere.json", "name": "x"})"
                                                << "at /extends: the experiment it extends";
        QTest::newRow("extends with no path") << R"({"extends": 3, "name": "x"})"
                                              << "at /extends: expected the path";
        QTest::newRow("extends itself")
            << R"({"extends": "experiment.json", "name": "x"})"
            << "at /extends: experiments extend each other in a circle (experiment.json -> "
               "experiment.json)";
        QTest::newRow("extends a scene") << R"({"extends": "good.json", "name": "x"})"
                                         << "neither 'scene' nor 'extends'";
        const QString trials =
            R"("following": {"trials": [{"object": {"shape": "rectangle", "offset_mm": [150, 150]}}]}, )";
        QTest::newRow("trial label with a comma")
            << head +
                   R"("following": {"trials": [{"label": "L, turned", "object": {"shape": "rectangle", "offset_mm": [150, 150]}}]}})"
            << "at /following/trials/0/label: 'L, turned' cannot name a trial";
        QTest::newRow("sweep: empty thresholds")
            << head + R"("sweeps": {"perception": {"belief_thresholds": []}}})"
            << "non-empty list";
        QTest::newRow("sweep: threshold of 1")
            << head + R"("sweeps": {"perception": {"belief_thresholds": [0.9, 1.0]}}})"
            << "/sweeps/perception/belief_thresholds/1";
        QTest::newRow("sweep: threshold of 0")
            << head + R"("sweeps": {"perception": {"belief_thresholds": [0]}}})"
            << "is not a belief threshold";
        QTest::newRow("sweep: negative step")
            << head + trials +
                   R"("sweeps": {"following": {"follow_steps_mm": [2, -1], "reposition_steps_mm": [1]}}})"
            << "/sweeps/following/follow_steps_mm/1";
        QTest::newRow("sweep: negative reposition")
            << head + trials +
                   R"("sweeps": {"following": {"follow_steps_mm": [2], "reposition_steps_mm": [-0.5]}}})"
            << "/sweeps/following/reposition_steps_mm/0";
        QTest::newRow("sweep: following without trials")
            << head +
                   R"("sweeps": {"following": {"follow_steps_mm": [2], "reposition_steps_mm": [1]}}})"
            << "needs trials";
        QTest::newRow("sweep: bandit without a following sweep")
            << head + trials + R"("sweeps": {"bandit": {"rounds": 10}}})"
            << "/sweeps/bandit/rounds: the bandit learns among the following sweep's active";
        QTest::newRow("sweep: bandit over passive settings only")
            << head + trials +
                   R"("sweeps": {"following": {"follow_steps_mm": [2], "reposition_steps_mm": [1], "modes": ["passive"]}, "bandit": {}}})"
            << "give sweeps.following with the active mode";
        QTest::newRow("sweep: bandit with a completion worth nothing")
            << head + trials +
                   R"("sweeps": {"following": {"follow_steps_mm": [2], "reposition_steps_mm": [1]}, "bandit": {"completion_worth_s": 0}}})"
            << "/sweeps/bandit/completion_worth_s";
        QTest::newRow("sweep: bandit with an unknown key")
            << head + trials +
                   R"("sweeps": {"following": {"follow_steps_mm": [2], "reposition_steps_mm": [1]}, "bandit": {"epsilon": 0.1}}})"
            << "epsilon";
        QTest::newRow("robustness: a taxel the fingertip does not have")
            << head + R"("sweeps": {"robustness": {"dead_taxels": [3, 12]}}})"
            << "/sweeps/robustness/dead_taxels: taxel 12 is not a taxel index 0..11";
        QTest::newRow("robustness: dead taxels neither each nor a list")
            << head + R"("sweeps": {"robustness": {"dead_taxels": "all"}}})"
            << "is \"each\" (every taxel in turn) or a list of taxel indices";
        QTest::newRow("robustness: no fault") << head + R"("sweeps": {"robustness": {}}})"
                                              << "a robustness sweep needs faults";
        QTest::newRow("robustness: a coupling past 0.5")
            << head + R"("sweeps": {"robustness": {"crosstalk_couplings": [0.1, 0.7]}}})"
            << "/sweeps/robustness/crosstalk_couplings/1";
        QTest::newRow("sweep: empty bins")
            << head + R"("sweeps": {"compute": {"bins": [], "samples_per_tap": [50]}}})"
            << "non-empty list";
        QTest::newRow("sweep: more samples than a tap has")
            << head + R"("sweeps": {"compute": {"bins": [100], "samples_per_tap": [60]}}})"
            << "up to the tap's 50";
    }
    void edgesNoTrainedOrientationFacesAreNamedBeforeAnyTap_data() {
        QTest::addColumn<QString>("object");
        QTest::addColumn<QString>("orientations");
        QTest::addColumn<QStringList>("expected");  // the caution's parts; empty: no caution
        const QString four = "[270, 0, 90, 180]";
        QTest::newRow("paper rectangle")
            << R"({"shape": "rectangle", "offset_mm": [150, 150]})" << four << QStringList{};
        QTest::newRow("C turned 180 deg: still right-angled and square to the stage")
            << R"({"shape": "c", "rotation_deg": 180, "offset_mm": [150, 150]})" << four
            << QStringList{};
        QTest::newRow("rectangle turned 5 deg: followed as well as square")
            << R"({"shape": "rectangle", "rotation_deg": 5, "offset_mm": [150, 150]})" << four
            << QStringList{};
        QTest::newRow("rectangle turned 10 deg")
            << R"({"shape": "rectangle", "rotation_deg": 10, "offset_mm": [150, 150]})" << four
            << QStringList{"/following/trials/0 (rectangle)", "4 of 4 edges face", "10 deg off"};
        QTest::newRow("triangle: its hypotenuse faces 45 deg")
            << R"({"shape": "polygon", "polygon_mm": [[0, 0], [40, 0], [0, 40]],
                   "offset_mm": [150, 150]})"
            << four
            << QStringList{"(polygon)", "1 of 3 edges faces", "from (190, 150) to (150, 190) mm",
                           "faces 45 deg, 45 deg off", "270, 0, 90, 180 deg"};
        QTest::newRow("triangle with the diagonals among the classes")
            << R"({"shape": "polygon", "polygon_mm": [[0, 0], [40, 0], [0, 40]],
                   "offset_mm": [150, 150]})"
            << "[270, 315, 0, 45, 90, 135, 180, 225]" << QStringList{};
    }
    void edgesNoTrainedOrientationFacesAreNamedBeforeAnyTap() {
        QFETCH(QString, object);
        QFETCH(QString, orientations);
        QFETCH(QStringList, expected);
        ExperimentSpec e = loadExperiment(test::sourcePath("experiments/paper.json"));
        e.classes.orientationsDeg =
            Json::parse(orientations.toStdString()).get<std::vector<double>>();
        TrialSpec trial = e.trials.front();
        trial.place = "/following/trials/0";
        trial.object =
            parseObject(JsonFields(Json::parse(object.toStdString()), "test", "/object"));
        trial.label = trial.object.shape;
        e.trials = {trial};
        const std::vector<std::string> cautions = untrainedEdgeCautions(e);
        if (expected.isEmpty()) {
            QVERIFY2(cautions.empty(), cautions.empty() ? "" : cautions.front().c_str());
            return;
        }
        QCOMPARE(int(cautions.size()), 1);
        const QString c = QString::fromStdString(cautions.front());
        for (const QString& part : expected) QVERIFY2(c.contains(part), qPrintable(c));
    }

    void badExperimentSettings() {
        QFETCH(QString, experiment);
        QFETCH(QString, problem);
        write("good.json", kGoodScene);
        // The object fits the travel, but the air side of its left edge does not.
        write("near_the_travel_end.json",
              QString(kGoodScene).replace("[150, 150]", "[25, 150]").toStdString());
        const std::string path = write("experiment.json", experiment.toStdString());
        try {
            loadExperiment(path);
            QFAIL("the experiment was accepted");
        } catch (const InputError& e) {
            QVERIFY2(QString(e.what()).contains(problem), e.what());
        }
    }
};

QTEST_APPLESS_MAIN(TestSceneFiles)
#include "test_scene_files.moc"
