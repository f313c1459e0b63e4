// The paper's outcomes, emerging from the simulated rig over ten whole runs (each seed its own
// data sets, training, valid range and trials): passive following loses the rectangle at its
// corners, active following completes the four shapes, recognition names the active paths. Two
// variants and what they cost: sequential perception in the loop (experiments/
// paper_sequential.json) pays taps for a small gain in completion, and five training taps per
// class (experiments/paper_five_training_taps.json) pays training time and completes more; a
// kernel-smoothed likelihood (experiments/paper_kernel.json) completes more at no extra tap, and
// so does following with a classifier trained again on every data set after validation
// (experiments/paper_retrained.json), which passive following gains from too (over seeds 1-100:
// 97.5 %, 97.5 %, 99.5 %, 98.5 % and 99.6 %; `activetouch-cli seeds` prints them). Two
// experiments compared trial by trial over the same seeds give each side's own rates, and
// McNemar's test on the trials they ended differently.
#include <QtTest>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <thread>

#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"
#include "core/run/ExperimentRun.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

class TestPaperReproduction : public QObject {
    Q_OBJECT
    std::vector<RunResult> runs_;
    SeedRates rates_, sequential_, fiveTaps_, kernel_, retrained_;

    static SeedRates seeds1To10(const char* experiment) {
        return runSeeds(simulatedRigs(), loadExperiment(test::sourcePath(experiment)), 1, 10, "");
    }
    static void report(const char* what, const SeedRates& r) {
        const Rate a = r.activeCompleted(), raw = r.recognisedRaw(), sm = r.recognisedSmoothed(),
                   p = r.passiveLost();
        qInfo(
            "%s: active %d of %d completed, passive %d of %d lost, recognised %d (smoothed %d) of "
            "%d; %.0f taps and %.0f s robot time per completed trial, %.0f s per whole run",
            what, a.count, a.total, p.count, p.total, raw.count, sm.count, raw.total,
            r.tapsPerCompletedTrial(), r.robotTimePerCompletedTrial_s(), r.robotTimePerRun_s());
        for (const auto& s : r.seeds)
            for (const auto& f : s.failures)
                qInfo("  seed %llu %s", static_cast<unsigned long long>(s.seed), f.c_str());
    }

private slots:
    void initTestCase() {
        // The paper's runs are kept whole: the tests look into their trials.
        const ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        for (std::uint64_t seed = 1; seed <= 10; ++seed) {
            RunOptions options = test::onSimulatedRig();
            options.seed = seed;
            runs_.push_back(runExperiment(spec, options));
            rates_.seeds.push_back(seedOutcome(runs_.back()));
        }
        sequential_ = seeds1To10("experiments/paper_sequential.json");
        fiveTaps_ = seeds1To10("experiments/paper_five_training_taps.json");
        kernel_ = seeds1To10("experiments/paper_kernel.json");
        retrained_ = seeds1To10("experiments/paper_retrained.json");
    }

    void passiveLosesTheRectangleAtItsCorners() {
        int trials = 0, lost = 0;
        for (const auto& run : runs_) {
            for (const auto& t : run.trials) {
                if (t.result.mode != FollowingMode::Passive) continue;
                ++trials;
                QCOMPARE(t.label, std::string("rectangle"));
                if (t.result.completed()) continue;
                // Where it went wrong: it had followed an edge up to a corner and got no further
                // (a rectangle's corners are all convex).
                lost += t.result.furthest.kind == PlaceKind::ConvexCorner;
                QVERIFY(t.result.furthestProgress_mm > 15.0);
            }
        }
        qInfo("passive: %d of %d trials lost at a corner", lost, trials);
        QCOMPARE(trials, 20);
        QVERIFY(lost >= 18);
        QCOMPARE(rates_.passiveLostAtCorner().count, lost);
        QCOMPARE(rates_.passiveLostAtCorner().total, 20);

        // A passive trial lost away from the corners is not the paper's result: the run falls
        // short and says which trial.
        RunResult run = runs_.front();
        QVERIFY(seedOutcome(run).paperResult());
        for (auto& t : run.trials)
            if (t.result.mode == FollowingMode::Passive && t.trial == 2)
                t.result.furthest.kind = PlaceKind::AwayFromCorners;
        SeedRates one;
        one.seeds.push_back(seedOutcome(run));
        const SeedOutcome& o = one.seeds.front();
        QCOMPARE(o.passiveLost, 2);
        QCOMPARE(o.passiveLostAtCorner(), 1);
        QVERIFY(!o.paperResult());
        QCOMPARE(one.shortOfPaper().passiveNotLost, 1);
        QCOMPARE(o.passiveShortfalls.size(), std::size_t(1));
        QVERIFY2(o.passiveShortfalls[0].rfind("passive rectangle trial 2: lost", 0) == 0,
                 o.passiveShortfalls[0].c_str());
        // The default seed shows the paper's result: both passive trials lost at a corner.
        for (const auto& t : runs_.front().trials)
            if (t.result.mode == FollowingMode::Passive) {
                QVERIFY(!t.result.completed());
                QCOMPARE(int(t.result.furthest.kind), int(PlaceKind::ConvexCorner));
            }
    }

    void cornersSayWhereTrialsStop() {
        // Every trial that did not complete is placed, near a convex or a concave corner or away
        // from corners; a completed trial got round each of its shape's corners once.
        const CornerTally active = rates_.corners(FollowingMode::Active),
                          passive = rates_.corners(FollowingMode::Passive);
        const Rate a = rates_.activeCompleted(), p = rates_.passiveLost();
        QCOMPARE(active.notCompleted(), a.total - a.count);
        QCOMPARE(passive.notCompleted(), p.count);
        QCOMPARE(passive.endedConvex + passive.endedConcave, rates_.passiveLostAtCorner().count);
        QCOMPARE(passive.endedConcave, 0);  // the rectangle has none
        for (const auto& run : runs_)
            for (const auto& t : run.trials) {
                if (!t.result.completed()) continue;
                CornerCount corners;
                for (std::size_t v = 0; v < t.outline.size(); ++v)
                    ++(t.outline.turnDeg(v) > 0 ? corners.convex : corners.concave);
                QCOMPARE(t.result.cornersRounded.convex, corners.convex);
                QCOMPARE(t.result.cornersRounded.concave, corners.concave);
            }
        // The paper's contrast, corner by corner: the active tip gets round nearly every corner,
        // of either kind; the passive tip gets round few.
        qInfo(
            "corners got round: active convex %d of %d, concave %d of %d; passive convex %d of "
            "%d",
            active.convexRounded().count, active.convexRounded().total,
            active.concaveRounded().count, active.concaveRounded().total,
            passive.convexRounded().count, passive.convexRounded().total);
        QVERIFY(active.convexRounded().fraction() > 0.95);
        QVERIFY(active.concaveRounded().fraction() > 0.95);
        QVERIFY(passive.convexRounded().fraction() < 0.5);
        QVERIFY(passive.convexRounded().total >= 20);  // every passive trial met a corner
        const Json j = seedRatesJson(rates_)["corners"];
        QCOMPARE(j["active"]["convex_corners_rounded"]["count"].get<int>(),
                 active.convexRounded().count);
        QCOMPARE(j["passive"]["not_completed_got_furthest_near"]["convex_corner"].get<int>(),
                 passive.endedConvex);
        const auto lines = describeRates(rates_);
        QVERIFY(std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
            return l.rfind("convex corners got round, passive ", 0) == 0;
        }));
    }

    void completionIsGivenPerValidRange() {
        // Each run's validation picks its own valid range; completion is summed over the runs that
        // picked each one, every run and trial counted once, labelled as the run prints it.
        const auto byRange = rates_.activeCompletedByValidRange();
        int runs = 0;
        Rate sum;
        for (const ValidRangeRate& v : byRange) {
            runs += v.runs;
            sum.count += v.activeCompleted.count;
            sum.total += v.activeCompleted.total;
            QCOMPARE(v.activeCompleted.total, 8 * v.runs);
        }
        QCOMPARE(runs, 10);
        QCOMPARE(sum.count, rates_.activeCompleted().count);
        QCOMPARE(sum.total, rates_.activeCompleted().total);
        const ValidRange& first = runs_.front().validation.validRange;
        QCOMPARE(rates_.seeds.front().validRange.first, first.first);
        QVERIFY(std::any_of(byRange.begin(), byRange.end(),
                            [&](const ValidRangeRate& v) { return v.range.first == first.first; }));
        for (std::size_t i = 1; i < byRange.size(); ++i)  // in the order of their positions
            QVERIFY(byRange[i - 1].range.first < byRange[i].range.first);
        const Json j = seedRatesJson(rates_);
        QCOMPARE(j["active_completed_by_valid_range"].size(), byRange.size());
        QCOMPARE(j["seeds"][0]["valid_range_positions"][0].get<int>(), first.first);
        const auto lines = describeRates(rates_);
        const bool several = byRange.size() > 1;
        QCOMPARE(std::count(lines.begin(), lines.end(),
                            "active trials completed by the valid range each run picked:"),
                 several ? 1 : 0);
    }

    void activeCompletesTheFourShapes() {
        const Rate a = rates_.activeCompleted();
        // A completed trial traced the contour closely: on average nearly all of it within
        // reach; a trial that came round having cut across part of it (a C's mouth, a corner)
        // is the exception. (Over seeds 1-1000, 6-7 % of seeds have a completed trial whose
        // path covers under 90 % of the contour.)
        int completed = 0, close = 0;
        double coverage = 0.0, distance = 0.0;
        for (const auto& run : runs_)
            for (const auto& t : run.trials)
                if (t.result.mode == FollowingMode::Active && t.result.completed()) {
                    ++completed;
                    coverage += t.result.coverage;
                    distance += t.result.meanContourDistance_mm;
                    close += t.result.coverage > 0.9 && t.result.meanContourDistance_mm < 2.0;
                }
        QVERIFY(completed > 0);
        QVERIFY2(coverage / completed > 0.97 && distance / completed < 1.2,
                 qPrintable(QString("coverage %1, distance %2 mm")
                                .arg(coverage / completed)
                                .arg(distance / completed)));
        QVERIFY2(close >= 0.95 * completed,
                 qPrintable(QString("%1 of %2").arg(close).arg(completed)));
        report("paper", rates_);
        QCOMPARE(a.total, 80);
        QVERIFY(a.count >= 72);  // at least 90 % over ten whole runs
        for (const auto& t : runs_.front().trials)
            if (t.result.mode == FollowingMode::Active)
                QVERIFY2(t.result.completed(), t.result.detail.c_str());
    }

    void ratesAreReportedPerShape() {
        // Active completion per trial label, in the experiment's order, adds up to the whole and
        // matches the trials it counts.
        const auto byLabel = rates_.activeCompletedByLabel();
        QCOMPARE(int(byLabel.size()), 4);
        const char* shapes[] = {"rectangle", "cross", "C", "L"};
        Rate sum;
        for (std::size_t i = 0; i < byLabel.size(); ++i) {
            const auto& [label, rate] = byLabel[i];
            QCOMPARE(label, std::string(shapes[i]));
            int trials = 0, completed = 0;
            for (const auto& run : runs_)
                for (const auto& t : run.trials)
                    if (t.result.mode == FollowingMode::Active && t.label == label) {
                        ++trials;
                        completed += t.result.completed();
                    }
            QCOMPARE(rate.total, trials);
            QCOMPARE(rate.count, completed);
            sum.count += rate.count;
            sum.total += rate.total;
        }
        QCOMPARE(sum.count, rates_.activeCompleted().count);
        QCOMPARE(sum.total, rates_.activeCompleted().total);
        const auto lines = describeRates(rates_);
        const auto cross = std::find_if(lines.begin(), lines.end(), [](const std::string& l) {
            return l.rfind("  cross ", 0) == 0;
        });
        QVERIFY(cross != lines.end());
        QVERIFY2(cross->find(QString("%1 / %2 ")
                                 .arg(byLabel[1].second.count)
                                 .arg(byLabel[1].second.total)
                                 .toStdString()) != std::string::npos,
                 cross->c_str());
        // One label only: no per-label lines (the paper's rule per trial number is another
        // breakdown, under its own line).
        SeedRates one;
        one.seeds.push_back(rates_.seeds.front());
        one.seeds.back().activeByLabel.resize(1);
        for (const auto& l : describeRates(one))
            QVERIFY2(l.rfind("  ", 0) != 0 || l.rfind("  trial ", 0) == 0, l.c_str());
    }

    void passiveRatesArePerShapeWhenSeveralShapesRunPassively() {
        // The cross followed passively beside the rectangle: each label's passive rate, in the
        // experiment's order, adds up to the whole and is printed under it.
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        spec.trials[2].mode = FollowingMode::Passive;  // the cross
        const SeedRates r = runSeeds(simulatedRigs(), spec, 1, 3, "");
        const auto byLabel = r.passiveLostByLabel();
        QCOMPARE(int(byLabel.size()), 2);
        QCOMPARE(byLabel[0].first, std::string("rectangle"));
        QCOMPARE(byLabel[1].first, std::string("cross"));
        QCOMPARE(byLabel[0].second.total, 6);
        QCOMPARE(byLabel[1].second.total, 6);
        QCOMPARE(byLabel[0].second.count + byLabel[1].second.count, r.passiveLost().count);
        QCOMPARE(int(r.activeCompletedByLabel().size()), 3);  // no cross among the active
        const auto lines = describeRates(r);
        const auto passive = std::find_if(lines.begin(), lines.end(), [](const std::string& l) {
            return l.rfind("passive trials lost", 0) == 0;
        });
        QVERIFY(passive != lines.end() && passive + 4 < lines.end());
        QVERIFY2((passive + 1)->rfind("  rectangle", 0) == 0, (passive + 1)->c_str());
        QVERIFY2((passive + 2)->rfind("  cross", 0) == 0, (passive + 2)->c_str());
        QVERIFY2((passive + 3)->rfind("passive trials lost at a corner", 0) == 0,
                 (passive + 3)->c_str());
        QVERIFY2((passive + 4)->rfind("active trials completed", 0) == 0, (passive + 4)->c_str());
        const Json j = seedRatesJson(r);
        QCOMPARE(j["passive_lost_by_label"].size(), std::size_t(2));
        QCOMPARE(j["passive_lost_by_label"][1]["label"].get<std::string>(), std::string("cross"));
        QCOMPARE(j["passive_lost_by_label"][1]["count"].get<int>(), byLabel[1].second.count);
    }

    void eightOrientationsFollowDiagonalEdges() {
        // Finer angular resolution, as the paper's conclusion proposes: classes every 45 deg,
        // trained on an octagon, follow the rectangle turned 45 deg and an octagon; the paper's
        // four orientations, trained on its rectangle, lose most of those trials.
        const ExperimentSpec eight =
            loadExperiment(test::sourcePath("experiments/eight_orientations.json"));
        QCOMPARE(eight.classes.orientationsDeg.size(), std::size_t(8));
        ExperimentSpec four = eight;
        four.classes.orientationsDeg = {270.0, 0.0, 90.0, 180.0};
        four.scene = loadExperiment(test::sourcePath("experiments/paper.json")).scene;
        const SeedRates r8 = runSeeds(simulatedRigs(), eight, 1, 10, ""),
                        r4 = runSeeds(simulatedRigs(), four, 1, 10, "");
        auto diagonal = [](const SeedRates& r) {
            Rate sum;
            for (const auto& [label, rate] : r.activeCompletedByLabel())
                if (label == "diamond" || label == "octagon") {
                    sum.count += rate.count;
                    sum.total += rate.total;
                }
            return sum;
        };
        const Rate d8 = diagonal(r8), d4 = diagonal(r4);
        qInfo("diamond and octagon completed: eight orientations %d of %d, four %d of %d", d8.count,
              d8.total, d4.count, d4.total);
        QCOMPARE(d8.total, 40);
        QVERIFY(d8.count >= 36);
        QVERIFY(d4.count <= 25);
        QCOMPARE(r8.recognisedSmoothed().count, r8.recognisedSmoothed().total);
    }

    void followingAloneNamesTheTrainingSettingsItWouldIgnore() {
        const RunResult& trained = runs_.front();
        ExperimentSpec spec = trained.spec;
        QVERIFY(trainingSettingsChanged(trained, spec).empty());
        spec.following.followStep_mm = 4.0;  // following settings are the trials' own
        spec.scene.seed = 7;
        QVERIFY(trainingSettingsChanged(trained, spec).empty());
        spec.classes.orientationsDeg = {270.0, 0.0};
        spec.training.retrainOnAllSets = true;
        const auto changed = trainingSettingsChanged(trained, spec);
        QCOMPARE(changed.size(), std::size_t(2));
        QCOMPARE(changed[0], std::string("edge orientations (deg): 270, 0, 90, 180 -> 270, 0"));
        QCOMPARE(changed[1], std::string("trained on every set: no -> yes"));
    }

    void runsShortOfThePapersResultSayWhere() {
        // Each run short of the paper's result is counted under every part it misses, and the
        // smoothed recognition rule can only add whole runs, never remove them.
        const ShortOfPaper s = rates_.shortOfPaper();
        QCOMPARE(s.runs, rates_.paperResult().total - rates_.paperResult().count);
        int passive = 0, active = 0, misnamed = 0;
        for (const SeedOutcome& o : rates_.seeds) {
            passive += o.passiveLostAtCorner() < o.passiveTrials;
            active += o.activeCompleted < o.activeTrials;
            misnamed += o.recognisedRaw() < o.recognitionTrials();
        }
        QCOMPARE(s.passiveNotLost, passive);
        QCOMPARE(s.activeLost, active);
        QCOMPARE(s.misnamedRaw, misnamed);
        QVERIFY(s.passiveNotLost + s.activeLost + s.misnamedRaw >= s.runs);
        QVERIFY(rates_.paperResultSmoothed().count >= rates_.paperResult().count);

        // A run whose only miss is one path misnamed by the paper's rule is whole with the
        // smoothed histograms, and the summary says which part it missed.
        SeedRates one;
        SeedOutcome o;
        o.passiveTrials = o.passiveLost = o.passiveCorners.endedConvex = 2;
        o.activeTrials = o.activeCompleted = 8;
        o.recognition = true;
        for (int trial = 1; trial <= 8; ++trial)
            o.namings.push_back(
                {"rectangle", trial, trial == 1 ? "C" : "rectangle", "rectangle", "", -1.0, -1.0});
        one.seeds.push_back(o);
        QCOMPARE(one.paperResult().count, 0);
        QCOMPARE(one.paperResultSmoothed().count, 1);
        const ShortOfPaper m = one.shortOfPaper();
        QCOMPARE(m.runs, 1);
        QCOMPARE(m.misnamedRaw, 1);
        QCOMPARE(m.passiveNotLost + m.activeLost, 0);
        const auto lines = describeRates(one);
        QVERIFY(std::find(lines.begin(), lines.end(),
                          "runs short: 1 (passive not lost at a corner 0, active lost 0, path "
                          "misnamed 1)") != lines.end());
        const Json j = seedRatesJson(one);
        QCOMPARE(j["paper_result_short_by"]["path_misnamed_paper_rule"].get<int>(), 1);
        QCOMPARE(j["paper_result_smoothed"]["count"].get<int>(), 1);
        QCOMPARE(j["seeds"][0]["paper_result_smoothed"].get<bool>(), true);
    }

    void recognitionConfusionSaysWhichShapesAreMisnamed() {
        // Over the ten runs: every recognised path in one cell of each rule's table, its row the
        // shape it traced, the diagonal the paths named rightly.
        const RecognitionConfusion c = rates_.confusion();
        QCOMPARE(c.labels, (std::vector<std::string>{"rectangle", "cross", "C", "L"}));
        int rawRight = 0, smoothedRight = 0, rawAll = 0, smoothedAll = 0, misnamedPaths = 0;
        for (std::size_t i = 0; i < c.labels.size(); ++i)
            for (std::size_t j = 0; j < c.labels.size(); ++j) {
                rawAll += c.raw[i][j];
                smoothedAll += c.smoothed[i][j];
                if (i == j) rawRight += c.raw[i][j], smoothedRight += c.smoothed[i][j];
            }
        QCOMPARE(rawAll, rates_.recognisedRaw().total);
        QCOMPARE(smoothedAll, rates_.recognisedSmoothed().total);
        QCOMPARE(rawRight, rates_.recognisedRaw().count);
        QCOMPARE(smoothedRight, rates_.recognisedSmoothed().count);
        for (const SeedOutcome& o : rates_.seeds) misnamedPaths += int(o.misnamed().size());
        QVERIFY(misnamedPaths >= rawAll - rawRight);

        // One run with a rectangle named C by the paper's rule only: the run, the table and the
        // summary each say so, and nothing is said of the smoothed rule.
        SeedRates one;
        SeedOutcome o;
        o.recognition = true;
        o.namings = {{"rectangle", 1, "C", "rectangle", "", -1.0, -1.0},
                     {"C", 1, "C", "C", "", -1.0, -1.0}};
        one.seeds.push_back(o);
        QCOMPARE(o.misnamed(),
                 (std::vector<std::string>{
                     "rectangle trial 1: C by the paper's rule, rectangle smoothed"}));
        const RecognitionConfusion m = one.confusion();
        QCOMPARE(m.labels, (std::vector<std::string>{"rectangle", "C"}));
        QCOMPARE(m.raw, (std::vector<std::vector<int>>{{0, 1}, {0, 1}}));
        QCOMPARE(m.smoothed, (std::vector<std::vector<int>>{{1, 0}, {0, 1}}));
        QCOMPARE(m.misnamed(false), std::string("rectangle as C 1"));
        QCOMPARE(m.misnamed(true), std::string());
        const auto lines = describeRates(one);
        QCOMPARE(std::count(lines.begin(), lines.end(), "  misnamed: rectangle as C 1"), 1);
        QCOMPARE(std::count_if(lines.begin(), lines.end(),
                               [](const std::string& l) { return l.find("misnamed:") == 2; }),
                 1);
        const Json j = seedRatesJson(one);
        QCOMPARE(j["recognition_confusion"]["paper_rule"][0][1].get<int>(), 1);
        QCOMPARE(j["recognition_confusion"]["smoothed"][0][0].get<int>(), 1);
        QCOMPARE(j["seeds"][0]["misnamed_paths"].size(), std::size_t(1));
    }

    void ratesWithoutThePapersPartsSayNone() {
        // Active trials only, no recognition (as experiments/feature_size.json): nothing is
        // reported as recognised or as the paper's result, rather than as 0 %.
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        spec.recognition.enabled = false;
        std::erase_if(spec.trials,
                      [](const TrialSpec& t) { return t.mode == FollowingMode::Passive; });
        RunOptions options = test::onSimulatedRig();
        options.seed = 1;
        SeedRates rates;
        rates.seeds.push_back(seedOutcome(runExperiment(spec, options)));
        const SeedOutcome& o = rates.seeds.front();
        QCOMPARE(o.activeTrials, 8);
        QVERIFY(!o.paperResultApplies());
        QVERIFY(!o.paperResult());
        for (const Rate& r :
             {rates.passiveLost(), rates.passiveLostAtCorner(), rates.recognisedRaw(),
              rates.recognisedSmoothed(), rates.paperResult(), rates.paperResultSmoothed()})
            QCOMPARE(r.total, 0);
        int none = 0;
        for (const auto& line : describeRates(rates))
            none += line.find("none in this experiment") != std::string::npos;
        QCOMPARE(none, 6);
        const Json j = seedRatesJson(rates);
        QVERIFY(j["seeds"][0]["paper_result"].is_null());
        QVERIFY(j["paper_result"]["rate"].is_null());
        QCOMPARE(rates.shortOfPaper().runs, 0);
    }

    void recognitionNamesTheActivePaths() {
        for (const auto& run : runs_)
            for (const auto& t : run.trials)
                if (t.recognised) QCOMPARE(int(t.recognition.distances.size()), 4);
        const Rate raw = rates_.recognisedRaw(), smoothed = rates_.recognisedSmoothed();
        qInfo("recognition of completed active paths: paper's rule %d of %d, smoothed %d of %d",
              raw.count, raw.total, smoothed.count, smoothed.total);
        QCOMPARE(smoothed.count, smoothed.total);
        QVERIFY(raw.count >= raw.total * 9 / 10);
        QCOMPARE(runs_.front().recognitionAccuracy, 1.0);
        QCOMPARE(runs_.front().recognitionAccuracySmoothed, 1.0);
    }

    void theNoiseFloorIsMeasuredOnTheRig() {
        // A tap is 600 readings: with the paper scene's taxel noise its peak over nothing lies
        // several counts up, far above the scene's 1-count floor, and the run measures it from
        // its own taps in the air (10 classes x 5 data sets).
        for (const auto& run : runs_) {
            QVERIFY(run.measuredNoiseFloor.has_value());
            QCOMPARE(run.measuredNoiseFloor->taps, 50);
            QVERIFY2(run.noiseFloor_counts >= 3.0 * 1.5 && run.noiseFloor_counts <= 15.0,
                     qPrintable(QString::number(run.noiseFloor_counts)));
            QCOMPARE(run.noiseFloor_counts, run.measuredNoiseFloor->counts);
        }
        // On the ideal rig nothing reads in the air: the scene's floor stands and the region map
        // is the geometry's alone.
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        spec.scene.effects.clear();
        spec.trials.clear();
        const RunResult ideal = runExperiment(spec, test::onSimulatedRig());
        QVERIFY(ideal.measuredNoiseFloor.has_value());
        QCOMPARE(ideal.measuredNoiseFloor->counts, 0.0);
        QCOMPARE(ideal.noiseFloor_counts, spec.scene.tap.noiseFloor);
        const FingertipContactModel model(spec.scene.fingertip);
        QVERIFY(ideal.classes.regions == computeClassRegions(model, spec.classes, spec.scene.tap,
                                                             spec.scene.strokeLimitDepth()));
    }

    void sequentialPerceptionPaysInTaps() {
        // Tapping again until the belief is sure costs taps at every uncertain place; the
        // misreadings that lose trials near corners are mostly the same tap after tap there, so
        // it completes little more (seeds 1-100: 97.5 % against 97.5 %; trial by trial over seeds
        // 1-1000, `activetouch-cli compare`: 97.3 % against 96.6 %).
        report("sequential", sequential_);
        const Rate a = sequential_.activeCompleted();
        QCOMPARE(a.total, 80);
        QVERIFY(a.count >= 72);
        QCOMPARE(sequential_.recognisedSmoothed().count, a.count);
        QVERIFY(sequential_.tapsPerCompletedTrial() > rates_.tapsPerCompletedTrial());
        QVERIFY(sequential_.robotTimePerCompletedTrial_s() > rates_.robotTimePerCompletedTrial_s());
    }

    void moreTrainingTapsPayInTrainingTime() {
        // Five training taps per class widen the likelihood histograms past one tap's noise:
        // fewer misreadings near corners, at five times the training taps.
        report("five training taps", fiveTaps_);
        const Rate a = fiveTaps_.activeCompleted();
        QCOMPARE(a.total, 80);
        QVERIFY(a.count >= rates_.activeCompleted().count);
        QCOMPARE(fiveTaps_.recognisedSmoothed().count, a.count);
        QVERIFY(fiveTaps_.robotTimePerRun_s() > 1.5 * rates_.robotTimePerRun_s());
    }

    void aKernelWidensTheLikelihoodsWithoutExtraTaps() {
        // The same one training tap per class, each count spread over its neighbouring bins: the
        // likelihoods are no longer as narrow as one tap's noise, and training costs nothing more.
        report("kernel", kernel_);
        const Rate a = kernel_.activeCompleted();
        QCOMPARE(a.total, 80);
        QVERIFY(a.count >= rates_.activeCompleted().count);
        QCOMPARE(kernel_.recognisedSmoothed().count, a.count);
        QVERIFY(kernel_.passiveLost().count >= 18);
        // Training and validation tap the same poses as the paper's: any difference in robot
        // time per run is the trials'.
        QVERIFY(kernel_.robotTimePerRun_s() < 1.1 * rates_.robotTimePerRun_s());
    }

    void pairedRatesAreExact() {
        // McNemar's exact test on the pairs that disagree, against hand-worked binomial tails.
        PairedRate r;
        QCOMPARE(r.mcnemarP(), 1.0);  // nothing compared, nothing different
        for (int i = 0; i < 5; ++i) r.add(false, true);
        QCOMPARE(r.mcnemarP(), 2.0 / 32.0);  // 0 of 5 one way: 2 * (1/2)^5
        r.add(true, false);
        for (int i = 0; i < 4; ++i) r.add(false, true);
        QCOMPARE(r.onlyA, 1);
        QCOMPARE(r.onlyB, 9);
        QVERIFY(qAbs(r.mcnemarP() - 2.0 * 11.0 / 1024.0) < 1e-12);  // 1 of 10: 2 * (1 + 10) / 2^10
        for (int i = 0; i < 90; ++i) r.add(i < 80, i < 80);
        QCOMPARE(r.pairs(), 100);
        QCOMPARE(r.a().count, 81);
        QCOMPARE(r.b().count, 89);
        QCOMPARE(r.difference(), 0.08);
        // Agresti and Min's interval: half a pair in each cell, n' = 102, discordant 1.5 and 9.5.
        const double d = 8.0 / 102.0, se = std::sqrt(11.0 - 64.0 / 102.0) / 102.0;
        QVERIFY(qAbs(r.differenceLow() - (d - 1.959963984540054 * se)) < 1e-12);
        QVERIFY(qAbs(r.differenceHigh() - (d + 1.959963984540054 * se)) < 1e-12);
        QVERIFY(r.differenceLow() > 0.0);  // 9 against 1 is a difference at 95 %
        // Evenly split disagreements: no evidence either way.
        PairedRate even;
        for (int i = 0; i < 3; ++i) {
            even.add(true, false);
            even.add(false, true);
        }
        QCOMPARE(even.mcnemarP(), 1.0);
        QCOMPARE(even.difference(), 0.0);
        QVERIFY(even.differenceLow() < 0.0 && even.differenceHigh() > 0.0);
        // Hundreds of disagreements stay finite in the log domain.
        PairedRate many;
        for (int i = 0; i < 600; ++i) many.add(i % 3 == 0, i % 3 != 0);
        QVERIFY(many.mcnemarP() > 0.0 && many.mcnemarP() < 1e-10);
    }

    void anExperimentComparedWithItselfDiffersNowhere() {
        PairedComparison c;
        std::vector<PairedTrial> pairs;
        for (const RunResult& run : runs_) addSeed(c, run, run, &pairs);
        QCOMPARE(c.seeds, 10);
        QCOMPARE(c.unpairedTrials, 0);
        QCOMPARE(c.activeCompleted.pairs(), 80);
        QCOMPARE(c.passiveLostAtCorner.pairs(), 20);
        QCOMPARE(c.paperResult.pairs(), 10);
        QCOMPARE(int(pairs.size()), 100);
        for (const PairedRate* r :
             {&c.activeCompleted, &c.passiveLostAtCorner, &c.recognisedRaw, &c.paperResult}) {
            QCOMPARE(r->onlyA + r->onlyB, 0);
            QCOMPARE(r->mcnemarP(), 1.0);
        }
        for (const PairedTrial& p : pairs) QCOMPARE(p.outcomeA, p.outcomeB);
        QCOMPARE(c.robotTimeDifferenceSd_s(), 0.0);
        auto said = [](const PairedComparison& x) {
            QString all;
            for (const std::string& line : describeComparison(x))
                all += QString::fromStdString(line) + '\n';
            return all;
        };
        QVERIFY2(said(c).contains("B - A +0.0 min per run (sd 0.0 min over the seeds)"),
                 qPrintable(said(c)));
        // One seed has no spread to give.
        PairedComparison one;
        addSeed(one, runs_[0], runs_[1]);
        QVERIFY2(said(one).contains("min per run\n"), qPrintable(said(one)));
    }

    void seedsRunSideBySideGiveWhatOneAfterAnotherGives() {
        // Three seeds at a time give each seed's outcome as the runs one after another did, and
        // report them in seed order; a stop after the fourth keeps four.
        const ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        std::vector<std::uint64_t> heard;
        const SeedRates side = runSeeds(
            simulatedRigs(), spec, 1, 10, "",
            [&](const SeedOutcome& o) {
                heard.push_back(o.seed);
                return true;
            },
            3);
        QCOMPARE(heard, (std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
        QCOMPARE(side.seeds.size(), rates_.seeds.size());
        for (std::size_t i = 0; i < side.seeds.size(); ++i) {
            const SeedOutcome &a = side.seeds[i], &b = rates_.seeds[i];
            QCOMPARE(a.seed, b.seed);
            QCOMPARE(a.activeCompleted, b.activeCompleted);
            QCOMPARE(a.passiveLost, b.passiveLost);
            QCOMPARE(a.failures, b.failures);
            QCOMPARE(a.misnamed(), b.misnamed());
            QCOMPARE(a.runRobotTime_s, b.runRobotTime_s);
            QCOMPARE(a.angleError_deg, b.angleError_deg);
        }
        const SeedRates stopped = runSeeds(
            simulatedRigs(), spec, 1, 10, "", [](const SeedOutcome& o) { return o.seed < 4; }, 3);
        QCOMPARE(stopped.seeds.size(), std::size_t(4));
        QCOMPARE(stopped.seeds.back().seed, std::uint64_t(4));
    }

    void seedsAreHandedOnInOrderWhateverFinishesFirst() {
        // Every third seed is slow, so later seeds finish before it: they still come after it.
        std::vector<std::uint64_t> order;
        forEachSeed(
            1, 9, 3,
            [](std::uint64_t seed) {
                if (seed % 3 == 1) std::this_thread::sleep_for(std::chrono::milliseconds(40));
                return seed * 10;
            },
            [&](std::uint64_t seed, std::uint64_t&& result) {
                order.push_back(result == seed * 10 ? seed : 0);  // 0: another seed's result
                return true;
            });
        QCOMPARE(order, (std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
        // A seed that fails reaches the caller after the seeds before it, and none after it.
        order.clear();
        QString failure;
        try {
            forEachSeed(
                1, 9, 3,
                [](std::uint64_t seed) {
                    if (seed == 5) throw std::runtime_error("seed 5 failed");
                    return seed;
                },
                [&](std::uint64_t seed, std::uint64_t&&) {
                    order.push_back(seed);
                    return true;
                });
        } catch (const std::runtime_error& e) {
            failure = e.what();
        }
        QCOMPARE(failure, QString("seed 5 failed"));
        QCOMPARE(order, (std::vector<std::uint64_t>{1, 2, 3, 4}));
        // The largest seeds end the range without wrapping round to 0.
        order.clear();
        const std::uint64_t top = std::numeric_limits<std::uint64_t>::max();
        forEachSeed(
            top - 2, top, 2, [](std::uint64_t seed) { return seed; },
            [&](std::uint64_t seed, std::uint64_t&&) {
                order.push_back(seed);
                return true;
            });
        QCOMPARE(order, (std::vector<std::uint64_t>{top - 2, top - 1, top}));
        // An empty range runs nothing; a single seed, and no jobs asked for, run one.
        order.clear();
        const auto keep = [&](std::uint64_t seed, std::uint64_t&&) {
            order.push_back(seed);
            return true;
        };
        const auto same = [](std::uint64_t seed) { return seed; };
        forEachSeed(5, 4, 2, same, keep);
        QVERIFY(order.empty());
        forEachSeed(7, 7, 0, same, keep);
        QCOMPARE(order, (std::vector<std::uint64_t>{7}));
    }

    void comparingTwoExperimentsPairsTheirSeedsRates() {
        // The paper against its kernel variant, trial by trial over the same seeds: each side's
        // totals are that experiment's own rates, and every trial the two ended differently is
        // among the disagreements.
        std::vector<int> heard;  // seeds compared, as each seed reports it
        const PairedComparison c = comparePaired(
            simulatedRigs(), loadExperiment(test::sourcePath("experiments/paper.json")),
            loadExperiment(test::sourcePath("experiments/paper_kernel.json")), 1, 10, "",
            [&](std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                const PairedComparison& soFar) {
                heard.push_back(soFar.seeds);
                return pairs.size() == 10 && pairs.front().seed == seed;
            });
        QCOMPARE(c.seeds, 10);
        QCOMPARE(heard, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
        // How the comparison stood after each seed: pairs only accumulate, and it ends where
        // the totals are.
        QCOMPARE(c.soFar.size(), std::size_t(10));
        for (std::size_t i = 0; i < c.soFar.size(); ++i) {
            QCOMPARE(c.soFar[i].activeCompleted.pairs(), 8 * int(i + 1));
            QCOMPARE(c.soFar[i].paperResult.pairs(), int(i + 1));
            if (i > 0)
                QVERIFY(c.soFar[i].activeCompleted.onlyB >= c.soFar[i - 1].activeCompleted.onlyB);
        }
        QCOMPARE(c.soFar.back().activeCompleted.onlyA, c.activeCompleted.onlyA);
        QCOMPARE(c.soFar.back().activeCompleted.onlyB, c.activeCompleted.onlyB);
        QCOMPARE(c.soFar.back().recognisedRaw.both, c.recognisedRaw.both);
        QCOMPARE(c.soFar.back().passiveLostAtCorner.neither, c.passiveLostAtCorner.neither);
        QCOMPARE(c.activeCompleted.a().count, rates_.activeCompleted().count);
        QCOMPARE(c.activeCompleted.b().count, kernel_.activeCompleted().count);
        QCOMPARE(c.activeCompleted.pairs(), 80);
        QCOMPARE(c.passiveLostAtCorner.a().count, rates_.passiveLostAtCorner().count);
        QCOMPARE(c.passiveLostAtCorner.b().count, kernel_.passiveLostAtCorner().count);
        QCOMPARE(c.paperResult.a().count, rates_.paperResult().count);
        QCOMPARE(c.paperResult.b().count, kernel_.paperResult().count);
        QCOMPARE(c.activeCompleted.onlyB - c.activeCompleted.onlyA,
                 kernel_.activeCompleted().count - rates_.activeCompleted().count);
        QCOMPARE(c.meanRobotTimeA_s(), rates_.robotTimePerRun_s());
        QCOMPARE(c.meanRobotTimeB_s(), kernel_.robotTimePerRun_s());
        // The two share their training taps: some trials end alike, some do not.
        QVERIFY(c.activeCompleted.both > 70);
    }

    void retrainingOnEverySetFollowsWithEveryTapTaken() {
        // The validation stays the paper's, set 1 against sets 2-5, to the last digit; only the
        // classifier the trials follow with learns from all five sets, at no extra tap.
        const ExperimentSpec spec =
            loadExperiment(test::sourcePath("experiments/paper_retrained.json"));
        RunOptions options = test::onSimulatedRig();
        options.seed = 1;
        const RunResult r = runExperiment(spec, options);
        const RunResult& paper = runs_.front();
        QCOMPARE(r.taps.size(), paper.taps.size());
        QCOMPARE(r.validation.angleError_deg, paper.validation.angleError_deg);
        QCOMPARE(r.validation.positionError_mm, paper.validation.positionError_mm);
        QCOMPARE(r.validation.validRange.first, paper.validation.validRange.first);
        QCOMPARE(r.validation.validRange.last, paper.validation.validRange.last);
        QCOMPARE(r.validOffsets.trustedLow, paper.validOffsets.trustedLow);
        QCOMPARE(r.validOffsets.trustedHigh, paper.validOffsets.trustedHigh);

        std::vector<LabelledTap> everyTap;
        for (const auto& t : r.taps) everyTap.push_back({&t.record.tap, t.cls});
        const HistogramClassifier everySet =
            HistogramClassifier::train(everyTap, r.classes.classCount(), spec.classifier);
        int changed = 0;
        for (const auto& t : r.taps) {
            QCOMPARE(r.classifier.classify(t.record.tap), everySet.classify(t.record.tap));
            changed +=
                r.classifier.classify(t.record.tap) != paper.classifier.classify(t.record.tap);
        }
        QVERIFY2(changed > 0, "the trials follow with set 1's classifier");
        QCOMPARE(r.classifierRetrainedOnTaps, int(r.taps.size()));
        QVERIFY2(
            followingClassifierNote(r).find("on all 5 data sets (360 taps") != std::string::npos,
            followingClassifierNote(r).c_str());
        QVERIFY(followingClassifierNote(paper).empty());
        // Following again with that classifier (the window's "Run following") says the same.
        ExperimentSpec oneTrial = spec;
        oneTrial.trials.resize(1);
        const RunResult again = runFollowing(r, oneTrial, test::onSimulatedRig());
        QCOMPARE(followingClassifierNote(again), followingClassifierNote(r));

        // What it buys, over ten whole runs: active following completes at least as often as
        // with set 1's classifier and nearly always, for the same robot time in training.
        report("paper, retrained on every set", retrained_);
        const Rate a = retrained_.activeCompleted();
        QCOMPARE(a.total, 80);
        QVERIFY(a.count >= rates_.activeCompleted().count);
        QVERIFY(a.count >= 78);
        QCOMPARE(retrained_.recognisedSmoothed().count, retrained_.recognisedSmoothed().total);
    }

    void completedTrialsSayHowCloselyTheyTraced() {
        // Over the ten paper runs: the completed trials of each mode, their mean coverage and
        // distance to the contour, as the trials themselves give them.
        for (const FollowingMode mode : {FollowingMode::Active, FollowingMode::Passive}) {
            int n = 0;
            double coverage = 0.0, distance = 0.0;
            for (const auto& run : runs_)
                for (const auto& t : run.trials)
                    if (t.result.mode == mode && t.result.completed()) {
                        ++n;
                        coverage += t.result.coverage;
                        distance += t.result.meanContourDistance_mm;
                    }
            const Tracing traced = rates_.tracing(mode);
            QCOMPARE(traced.trials, n);
            QVERIFY(n > 0);
            QVERIFY(qFuzzyCompare(traced.coverage(), coverage / n));
            QVERIFY(qFuzzyCompare(traced.meanDistance_mm(), distance / n));
        }
        QCOMPARE(rates_.tracing(FollowingMode::Active).trials, rates_.activeCompleted().count);
        QCOMPARE(rates_.tracing(FollowingMode::Passive).trials,
                 rates_.passiveLost().total - rates_.passiveLost().count);

        // A passive trial that gets round never corrects its offset from the edge: with the
        // classifier trained on every set it gets round more often, and traces the contour less
        // closely and less completely than the active trials.
        const Tracing active = retrained_.tracing(FollowingMode::Active),
                      passive = retrained_.tracing(FollowingMode::Passive);
        qInfo("retrained: completed active %.1f %% covered, %.2f mm; passive (%d) %.1f %%, %.2f mm",
              100 * active.coverage(), active.meanDistance_mm(), passive.trials,
              100 * passive.coverage(), passive.meanDistance_mm());
        QVERIFY(passive.trials > 0);
        QVERIFY(passive.coverage() < active.coverage());
        QVERIFY(passive.meanDistance_mm() > active.meanDistance_mm());
        const auto lines = describeRates(retrained_);
        QVERIFY(std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
            return l.rfind("completed passive trials: ", 0) == 0;
        }));

        // No passive trial got round: no passive line, and nothing to average in rates.json.
        SeedRates none;
        none.seeds.push_back(rates_.seeds.front());
        QCOMPARE(none.seeds.front().passiveTracing.trials, 0);
        for (const auto& l : describeRates(none))
            QVERIFY2(l.rfind("completed passive trials", 0) != 0, l.c_str());
        const Json j = seedRatesJson(none)["completed_tracing"];
        QVERIFY(j["passive"]["coverage_mean"].is_null());
        QCOMPARE(j["active"]["trials"].get<int>(), 8);
        QVERIFY(j["active"]["coverage_mean"].get<double>() > 0.9);
    }
};

QTEST_APPLESS_MAIN(TestPaperReproduction)
#include "test_paper_reproduction.moc"
