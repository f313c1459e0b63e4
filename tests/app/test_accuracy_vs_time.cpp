// The accuracy-versus-time sweeps show their expected shape on the simulated rig, over three
// whole runs: one tap's calibrated belief means what it says on fresh taps; belief thresholds
// from 0.5 to 0.999 span one to several taps per decision, and more taps lower the perception
// error; coarser histograms and fewer samples cost accuracy; following trades robot time against
// path error, and accumulating evidence costs robot time. Over seeds, each figure is the mean of
// the seeds' figures, the following settings are paired with the paper's seed by seed, and what
// a seed keeps of its sweeps reads back to the same rates.
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>

#include "core/analysis/SeedRates.h"
#include "core/analysis/SweepRates.h"
#include "core/experiment/RunPlan.h"
#include "core/run/ExperimentRun.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

class TestAccuracyVsTime : public QObject {
    Q_OBJECT
    std::vector<RunResult> runs_;

private slots:
    void initTestCase() {
        const ExperimentSpec spec =
            loadExperiment(test::sourcePath("experiments/accuracy_vs_time.json"));
        for (std::uint64_t seed : {1u, 2u, 3u}) {
            RunOptions options = test::onSimulatedRig();
            options.seed = seed;
            runs_.push_back(runExperiment(spec, options));
        }
    }

    void moreTapsPerDecisionLowerTheError() {
        const std::size_t n = runs_.front().sweeps.perception.size();
        std::vector<double> taps(n), position(n), correct(n);
        for (const auto& r : runs_) {
            QCOMPARE(r.sweeps.perception.size(), n);
            for (std::size_t i = 0; i < n; ++i) {
                taps[i] += r.sweeps.perception[i].meanTaps / runs_.size();
                position[i] += r.sweeps.perception[i].positionError_mm / runs_.size();
                correct[i] += r.sweeps.perception[i].correctFraction / runs_.size();
            }
        }
        for (std::size_t i = 1; i < n; ++i)
            QVERIFY(taps[i] >= taps[i - 1]);  // higher thresholds take more taps
        QVERIFY(taps.back() > taps.front() + 0.3);
        QVERIFY2(position.back() < position.front(),
                 qPrintable(QString("%1 -> %2 mm").arg(position.front()).arg(position.back())));
        QVERIFY(correct.back() > correct.front());
        qInfo(
            "sequential perception: %.2f -> %.2f taps per decision, position error %.3f -> %.3f "
            "mm, correct %.1f -> %.1f %%",
            taps.front(), taps.back(), position.front(), position.back(), 100 * correct.front(),
            100 * correct.back());
    }

    void calibratedBeliefMeansWhatItSays() {
        // A calibrated belief's ECE is near what sampling alone gives a perfectly calibrated one
        // (about 0.02 on these taps): over the seeds at most 0.05 on average, no seed beyond
        // 0.065 (one seed's ECE moves by about 0.01 with the taps it is measured on); raw, it is
        // ten times that.
        double calibrated = 0.0;
        for (const auto& r : runs_) {
            // On taps that neither trained the classifier nor fitted the calibration.
            const PerceptionSweepCalibration& c = r.sweeps.perceptionCalibration;
            QVERIFY(c.measured && c.calibrated && c.taps >= 1000);
            qInfo("seed %d: ECE %.3f raw, %.3f calibrated (%.3f if perfectly calibrated)",
                  int(r.spec.scene.seed), c.eceRaw, c.eceCalibrated, c.eceIfCalibrated);
            QVERIFY(c.eceRaw > 0.25);
            QVERIFY(c.eceCalibrated <= 0.065);
            calibrated += c.eceCalibrated / double(runs_.size());
            // Evidence over repeated taps is worth less than a single tap's scaling says.
            QVERIFY(r.beliefCalibration.sequential.scale < r.beliefCalibration.scaling.scale);
        }
        QVERIFY2(calibrated <= 0.05, qPrintable(QString::number(calibrated)));
    }

    void thresholdsSpanDecisionTimesAndErrorsFall() {
        // Each run's falls in angle and position error, pooled over the runs: the mean of the
        // runs' means, its standard error from each run's interval (95 %: 1.96 standard errors).
        double angleFalls = 0.0, angleVariance = 0.0, positionFalls = 0.0, positionVariance = 0.0;
        const auto variance = [](double low, double high) {
            const double se = (high - low) / (2.0 * 1.96);
            return se * se;
        };
        for (const auto& r : runs_) {
            const auto& rows = r.sweeps.perception;
            QVERIFY(rows.size() >= 2);
            const PerceptionSweepRow& first = rows.front();
            const PerceptionSweepRow& last = rows.back();
            QCOMPARE(first.threshold, 0.5);
            QCOMPARE(last.threshold, 0.999);
            qInfo(
                "seed %d: %.2f -> %.2f taps; edge angle %.2f (%.2f-%.2f) -> %.2f (%.2f-%.2f) deg; "
                "position %.3f (%.3f-%.3f) -> %.3f (%.3f-%.3f) mm",
                int(r.spec.scene.seed), first.meanTaps, last.meanTaps, first.angleError_deg,
                first.angle_deg.low, first.angle_deg.high, last.angleError_deg, last.angle_deg.low,
                last.angle_deg.high, first.positionError_mm, first.position_mm.low,
                first.position_mm.high, last.positionError_mm, last.position_mm.low,
                last.position_mm.high);
            QVERIFY(first.meanTaps < 2.0);
            QVERIFY(last.meanTaps >= 5.0);
            for (std::size_t i = 1; i < rows.size(); ++i) {
                QVERIFY(rows[i].meanTaps >= rows[i - 1].meanTaps);
                QVERIFY(rows[i].meanRobotTime_s >= rows[i - 1].meanRobotTime_s);
            }
            // The errors fall below single taps', paired decision by decision, in every run; over
            // the runs together by more than the pooled fall's interval.
            qInfo(
                "seed %d: below single taps at 0.999: angle %.2f (%.2f-%.2f) deg, position "
                "%.3f (%.3f-%.3f) mm",
                int(r.spec.scene.seed), last.angleFall_deg.mean, last.angleFall_deg.low,
                last.angleFall_deg.high, last.positionFall_mm.mean, last.positionFall_mm.low,
                last.positionFall_mm.high);
            QVERIFY(last.angleFall_deg.mean > 0.0 && last.positionFall_mm.mean > 0.0);
            angleFalls += last.angleFall_deg.mean;
            angleVariance += variance(last.angleFall_deg.low, last.angleFall_deg.high);
            positionFalls += last.positionFall_mm.mean;
            positionVariance += variance(last.positionFall_mm.low, last.positionFall_mm.high);
            // The paper's operating point on the same taps: one tap each.
            QCOMPARE(r.sweeps.perceptionSingleTap.meanTaps, 1.0);
            QCOMPARE(r.sweeps.perceptionSingleTap.angleFall_deg.mean, 0.0);
            // Plane and air are told apart from edges whatever the threshold.
            QVERIFY(first.planeDecisions > 0 && first.airDecisions > 0);
            QVERIFY(first.planeRecognised > 0.9 && first.airRecognised > 0.9);
        }
        const auto n = static_cast<double>(runs_.size());
        const double angleLow = angleFalls / n - 1.96 * std::sqrt(angleVariance) / n;
        const double positionLow = positionFalls / n - 1.96 * std::sqrt(positionVariance) / n;
        qInfo(
            "pooled over %d runs: angle falls %.2f deg (interval from %.2f), position %.3f mm "
            "(from %.3f)",
            int(runs_.size()), angleFalls / n, angleLow, positionFalls / n, positionLow);
        QVERIFY(angleLow > 0.0 && positionLow > 0.0);
    }

    void fewerSamplesAndBinsCostAccuracyAndSaveTime() {
        for (const auto& r : runs_) {
            const ComputeSweepRow* paper = nullptr;
            const ComputeSweepRow* fewest = nullptr;
            for (const auto& row : r.sweeps.compute) {
                if (row.paperSetting) paper = &row;
                if (row.samples == 5 && row.bins == 100) fewest = &row;
            }
            QVERIFY(paper && fewest);
            QVERIFY(fewest->angleError_deg > paper->angleError_deg);
            QVERIFY(fewest->positionError_mm > paper->positionError_mm);
            QVERIFY(fewest->microsecondsPerDecision < paper->microsecondsPerDecision);
        }
    }

    void followingTradesRobotTimeForPathError() {
        int cheaperComplete = 0;
        for (const auto& r : runs_) {
            const FollowingSweepRow* paper = nullptr;
            for (const auto& row : r.sweeps.following)
                if (row.paperSetting && row.mode == FollowingMode::Active) paper = &row;
            QVERIFY(paper);
            // Longer follow steps take less robot time per trial and follow less closely.
            double timeShort = 0, timeLong = 0, distShort = 0, distLong = 0;
            int nShort = 0, nLong = 0;
            bool sequentialCheaper = false;
            for (const auto& row : r.sweeps.following) {
                if (row.mode != FollowingMode::Active) continue;
                if (row.followStep_mm == 1.0) {
                    timeShort += row.meanRobotTime_s;
                    distShort += row.meanContourDistance_mm;
                    ++nShort;
                }
                if (row.followStep_mm == 4.0) {
                    timeLong += row.meanRobotTime_s;
                    distLong += row.meanContourDistance_mm;
                    ++nLong;
                }
                if (row.beliefThreshold > 0 && row.completed == row.trials &&
                    row.robotTimePerCompletion_s < paper->robotTimePerCompletion_s)
                    sequentialCheaper = true;
                // Accumulating evidence costs robot time at every step.
                if (row.beliefThreshold > 0)
                    for (const auto& single : r.sweeps.following)
                        if (single.mode == row.mode && single.beliefThreshold == 0 &&
                            single.followStep_mm == row.followStep_mm &&
                            single.repositionStep_mm == row.repositionStep_mm)
                            QVERIFY(row.meanTaps > single.meanTaps);
            }
            QVERIFY(timeLong / nLong < timeShort / nShort);
            QVERIFY(distLong / nLong > distShort / nShort);
            cheaperComplete += sequentialCheaper;
            // Passive never repositions and so loses the shapes whatever the step.
            for (const auto& row : r.sweeps.following)
                if (row.mode == FollowingMode::Passive) QVERIFY(row.completed <= row.trials / 4);
        }
        qInfo(
            "runs with a sequential setting completing every trial in less robot time than the "
            "paper's setting: %d of 3",
            cheaperComplete);
    }

    void theBanditLearnsASettingAndIsSetAgainstTheSweep() {
        for (const auto& r : runs_) {
            const BanditResult& b = r.sweeps.bandit;
            QVERIFY(b.ran);
            QCOMPARE(b.rounds, 144);
            int pulls = 0, active = 0;
            for (const auto& row : r.sweeps.following) active += row.mode == FollowingMode::Active;
            QCOMPARE(int(b.arms.size()), active);
            for (const BanditArm& a : b.arms) {
                QVERIFY(a.pulls >= 1);  // UCB1 tries every setting once
                QCOMPARE(r.sweeps.following[std::size_t(a.sweepRow)].mode, FollowingMode::Active);
                QVERIFY(std::abs(a.rewardSum - (a.completed - a.robotTime_s / 2000.0)) < 1e-6);
                QVERIFY(a.pulls <= b.arms[std::size_t(b.chosen)].pulls);  // its choice: run most
                pulls += a.pulls;
            }
            QCOMPARE(pulls, 144);
            QVERIFY(b.chosenSweepReward <= b.bestSweepReward);
            // The learner spends a fraction of what the sweep spends.
            QVERIFY(b.robotTime_s < b.sweepRobotTime_s);
            // It concentrates its trials: its choice ran more than the even share.
            QVERIFY(b.arms[std::size_t(b.chosen)].pulls > 144 / active);
        }
    }

    void sweepsOverSeedsAreMeansOverTheSeeds() {
        std::vector<SeedOutcome> outcomes;
        for (const auto& r : runs_) outcomes.push_back(seedOutcome(r));
        const SweepRates rates = sweepRates(outcomes);
        QCOMPARE(rates.seeds, 3);
        QCOMPARE(rates.perception.size(), runs_.front().sweeps.perception.size());
        for (std::size_t i = 0; i < rates.perception.size(); ++i) {
            double taps = 0, angle = 0;
            for (const auto& r : runs_) {
                taps += r.sweeps.perception[i].meanTaps / 3;
                angle += r.sweeps.perception[i].angleError_deg / 3;
            }
            QVERIFY(std::abs(rates.perception[i].taps.mean - taps) < 1e-12);
            QVERIFY(std::abs(rates.perception[i].angle_deg.mean - angle) < 1e-12);
            QVERIFY(rates.perception[i].angle_deg.low <= angle);
            QVERIFY(rates.perception[i].angle_deg.high >= angle);
            QVERIFY(rates.perception[i].angle_deg.low >= 0.0);  // an error is never negative
        }
        QCOMPARE(rates.calibrationSeeds, 3);
        // Each following setting against the paper's, seed by seed.
        std::size_t paper = rates.following.size();
        for (std::size_t i = 0; i < rates.following.size(); ++i)
            if (rates.following[i].paperSetting && rates.following[i].mode == FollowingMode::Active)
                paper = i;
        QVERIFY(paper < rates.following.size());
        QVERIFY(!rates.following[paper].paired && !rates.following[paper].beatsPaper);
        for (std::size_t i = 0; i < rates.following.size(); ++i) {
            const FollowingOverSeeds& f = rates.following[i];
            if (f.mode != FollowingMode::Active || i == paper) continue;
            QVERIFY(f.paired);
            double difference = 0, time = 0, paperTime = 0, completed = 0, paperCompleted = 0;
            for (const auto& r : runs_) {
                const FollowingSweepRow &a = r.sweeps.following[i], &b = r.sweeps.following[paper];
                difference +=
                    100.0 * (double(a.completed) / a.trials - double(b.completed) / b.trials) / 3;
                time += a.meanRobotTime_s * a.trials;
                paperTime += b.meanRobotTime_s * b.trials;
                completed += a.completed;
                paperCompleted += b.completed;
            }
            QVERIFY(std::abs(f.completionDifference_points.mean - difference) < 1e-9);
            if (completed > 0)
                QVERIFY(std::abs(f.timeRatio.mean -
                                 (time / completed) / (paperTime / paperCompleted)) < 1e-9);
        }
        // What a seed keeps reads back to the same rates.
        std::vector<SeedOutcome> kept;
        for (const SeedOutcome& o : outcomes) {
            SeedOutcome back = o;
            back.sweeps = seedSweepsFromJson(Json::parse(seedSweepsJson(o.sweeps).dump()));
            kept.push_back(back);
        }
        QCOMPARE(QString::fromStdString(sweepRatesJson(sweepRates(kept)).dump()),
                 QString::fromStdString(sweepRatesJson(rates).dump()));
        // The bandit over seeds: each seed's choice against that seed's best.
        QCOMPARE(rates.bandit.seeds, 3);
        int same = 0;
        for (const auto& r : runs_) same += r.sweeps.bandit.chosen == r.sweeps.bandit.sweepBest;
        QCOMPARE(rates.bandit.choseBest, same);
        QVERIFY(rates.bandit.regret.mean >= 0.0);
    }

    void aSettingBeatsThePaperOnlyFasterAtNoLossOfCompletion() {
        // Thirty seeds with three settings: the paper's; one that completes as often in two
        // thirds of the robot time; one faster still that loses a tenth of its trials.
        std::vector<SeedOutcome> seeds;
        for (int s = 0; s < 30; ++s) {
            SeedOutcome o;
            o.seed = s + 1;
            auto row = [&](double follow, bool paper, int completed, double time) {
                FollowingSweepRow r{FollowingMode::Active, follow, 1.0, 0.0};
                r.paperSetting = paper;
                r.trials = 10;
                r.completed = completed;
                r.meanRobotTime_s = time + 3.0 * (s % 3);
                r.meanContourDistance_mm = follow / 2;
                return r;
            };
            o.sweeps.following = {row(2, true, 10 - s % 2, 300), row(3, false, 10 - s % 2, 200),
                                  row(4, false, 9 - s % 2, 150)};
            seeds.push_back(o);
        }
        SeedOutcome failed;  // a run stopped by a rig error measured no sweep
        failed.seed = 31;
        failed.runFailure = "stage asked past its travel";
        seeds.push_back(failed);
        {
            // On ten seeds the same settings get no verdict: too few for the intervals to say.
            const std::vector<SeedOutcome> few(seeds.begin(), seeds.begin() + 10);
            const SweepRates early = sweepRates(few);
            QCOMPARE(early.following[1].pairedSeeds, 10);
            QVERIFY(early.following[1].verdict == PaperVerdict::NotEnoughSeeds);
            QVERIFY(!early.following[1].beatsPaper);
            bool said = false;
            for (const std::string& line : describeSweepRates(early))
                said =
                    said || line.find("not enough seeds yet for a verdict on") != std::string::npos;
            QVERIFY(said);
        }
        const SweepRates rates = sweepRates(seeds);
        QCOMPARE(rates.seeds, 30);
        QCOMPARE(rates.following[0].completed.total, 300);
        // Every seed gives the same completion difference (0): its interval is not the
        // zero-width "+0.0 (+0.0 to +0.0)" but the paired score interval over the 300 trials.
        QVERIFY(rates.following[1].completionDifference_points.low < 0 &&
                rates.following[1].completionDifference_points.high > 0);
        QVERIFY(rates.following[1].verdict == PaperVerdict::Beats);
        QVERIFY(rates.following[1].beatsPaper);
        QVERIFY(std::abs(rates.following[1].completionDifference_points.mean) < 1e-12);
        QVERIFY(rates.following[1].timeRatio.high < 1.0);
        QVERIFY(!rates.following[2].beatsPaper);  // faster, but completes less
        QVERIFY(rates.following[2].completionDifference_points.high < 0);
        // Every setting is on the front: each is faster or closer to the contour than the next.
        for (const auto& f : rates.following) QVERIFY(f.onParetoFront);
        // A setting slower, less complete and further from the contour is off it.
        for (auto& o : seeds)
            if (!o.failed()) {
                FollowingSweepRow worse = o.sweeps.following[0];
                worse.paperSetting = false;
                worse.completed -= 2;
                worse.meanRobotTime_s += 100;
                worse.meanContourDistance_mm += 1;
                o.sweeps.following.push_back(worse);
            }
        const SweepRates more = sweepRates(seeds);
        QVERIFY(!more.following[3].onParetoFront);
        QVERIFY(!more.following[3].beatsPaper);
        QVERIFY(more.following[0].onParetoFront);
    }

    void boundedQuantitiesHaveIntervalsInsideTheirRangeUncut() {
        // An error near 0 with one large seed: Student's t would reach below 0; the interval on
        // the log scale stays above it without being cut there, and keeps the mean inside.
        const SweepEstimate e = overSeeds({0.1, 0.2, 0.15, 5.0}, 0.0);
        QVERIFY2(e.low > 0.0 && e.low < e.mean && e.high > e.mean,
                 qPrintable(QString("%1 (%2 to %3)").arg(e.mean).arg(e.low).arg(e.high)));
        // A fraction near 1: inside (0, 1), never cut at 1.
        const SweepEstimate f = overSeeds({1.0, 1.0, 0.9, 1.0, 0.5}, 0.0, 1.0);
        QVERIFY(f.low > 0.0 && f.high < 1.0 && f.low < f.mean && f.mean < f.high);
        // Every seed at the bound: the mean and a zero-width interval there, no NaN.
        const SweepEstimate z = overSeeds({0.0, 0.0, 0.0}, 0.0);
        QVERIFY(z.mean == 0.0 && z.low == 0.0 && z.high == 0.0);
        // Unbounded: Student's t, symmetric.
        const SweepEstimate u = overSeeds({-1.0, 1.0, 0.0});
        QVERIFY(std::abs(u.low + u.high) < 1e-12 && u.high > 0);
    }

    void tablesHoldNoNanOrInfinity() {
        // A setting that never completes has no time per completion and no time ratio: the
        // tables leave those cells empty and the report prints a dash, never nan or inf.
        std::vector<SeedOutcome> seeds;
        for (int s = 0; s < 3; ++s) {
            SeedOutcome o;
            o.seed = s + 1;
            FollowingSweepRow paper{FollowingMode::Active, 2.0, 1.0, 0.0};
            paper.paperSetting = true;
            paper.trials = 4;
            paper.completed = 4;
            paper.meanRobotTime_s = 100;
            FollowingSweepRow never = paper;
            never.paperSetting = false;
            never.followStep_mm = 6.0;
            never.completed = 0;
            o.sweeps.following = {paper, never};
            seeds.push_back(o);
        }
        const SweepRates rates = sweepRates(seeds);
        QTemporaryDir dir;
        writeSweepRateTables(rates, dir.path().toStdString());
        QFile table(dir.filePath("sweeps_following.csv"));
        QVERIFY(table.open(QIODevice::ReadOnly));
        const QString text = table.readAll();
        const QRegularExpression nonFinite("\\b(nan|inf)\\b",
                                           QRegularExpression::CaseInsensitiveOption);
        QVERIFY2(!text.contains(nonFinite), qPrintable(text));
        bool dashed = false;
        for (const std::string& line : describeSweepRates(rates)) {
            QVERIFY2(!QString::fromStdString(line).contains(nonFinite), line.c_str());
            dashed = dashed || line.find("a dash: no value") != std::string::npos;
        }
        QVERIFY(dashed);
    }

    void eachFaultIsTheWholeRunOnItsFaultyScene() {
        // A robustness sweep's row for a fault is exactly the experiment run on the same seed
        // with that fault in its scene; its base row is the run itself.
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/robustness.json"));
        spec.trials.resize(1);  // the rectangle, twice
        spec.sweeps.faults = {spec.sweeps.faults[3], spec.sweeps.faults.back()};
        QCOMPARE(QString::fromStdString(spec.sweeps.faults[0].name), QString("dead taxel 3"));
        QCOMPARE(QString::fromStdString(spec.sweeps.faults[1].name), QString("crosstalk 0.2"));
        RunOptions options = test::onSimulatedRig();
        options.seed = 2;
        const RunResult run = runExperiment(spec, options);
        const auto& rows = run.sweeps.robustness;
        QCOMPARE(int(rows.size()), 2);
        const SeedOutcome self = seedOutcome(run);
        QCOMPARE(run.sweeps.robustnessBase.activeCompleted, self.activeCompleted);
        QCOMPARE(run.sweeps.robustnessBase.angleError_deg, run.validation.angleError_deg);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            ExperimentSpec faulty = spec;
            faulty.sweeps = {};
            faulty.scene.effects.push_back(spec.sweeps.faults[i].effect);
            const RunResult direct = runExperiment(faulty, options);
            const SeedOutcome o = seedOutcome(direct);
            QCOMPARE(rows[i].activeCompleted, o.activeCompleted);
            QCOMPARE(rows[i].activeTrials, o.activeTrials);
            QCOMPARE(rows[i].recognisedRaw, o.recognisedRaw());
            QCOMPARE(rows[i].angleError_deg, direct.validation.angleError_deg);
            QCOMPARE(rows[i].positionError_mm, direct.validation.positionError_mm);
        }
        // The fault changes what the fingertip reads: the validation is not the base's.
        QVERIFY(rows[0].angleError_deg != run.validation.angleError_deg ||
                rows[0].positionError_mm != run.validation.positionError_mm);
        // Over seeds, a fault's fall is the base's completion less its own, seed by seed.
        SeedOutcome a = self, b = self;
        a.seed = 1;
        b.seed = 2;
        a.sweeps.robustnessBase.activeCompleted = 2;
        a.sweeps.robustness[0].activeCompleted = 1;
        b.sweeps.robustnessBase.activeCompleted = 2;
        b.sweeps.robustness[0].activeCompleted = 2;
        const SweepRates rates = sweepRates({a, b});
        QCOMPARE(rates.robustness[0].completed.count, 3);
        QCOMPARE(rates.robustness[0].completed.total, 4);
        QVERIFY(std::abs(rates.robustness[0].completionFall_points.mean - 25.0) < 1e-9);
        QCOMPARE(QString::fromStdString(rates.robustness[0].fault), QString("dead taxel 3"));
    }

    void thePlanCountsTheBanditAndEveryFaultsRun() {
        // A plan that left out (d) or (e) would let a long sweep past the plan's bound unasked.
        const ExperimentSpec robust =
            loadExperiment(test::sourcePath("experiments/robustness.json"));
        const RunPlan p = planOf(robust);
        QCOMPARE(p.sweepTaps, double(robust.sweeps.faults.size()) * (p.trainingTaps + p.trialTaps));
        ExperimentSpec avt = loadExperiment(test::sourcePath("experiments/accuracy_vs_time.json"));
        const double with = planOf(avt).sweepTaps;
        avt.sweeps.bandit = false;
        QVERIFY(with > planOf(avt).sweepTaps);
    }

    void overSeedsIntervalsAreStudentsT() {
        const SweepEstimate none = overSeeds({});
        QCOMPARE(none.mean, 0.0);
        const SweepEstimate one = overSeeds({2.0}, 0.0, 5.0);
        QCOMPARE(one.mean, 2.0);
        QCOMPARE(one.low, 0.0);  // one seed says nothing of the spread
        QCOMPARE(one.high, 5.0);
        // 1, 2, 3: mean 2, standard error 1/sqrt(3), t(2) = 0.95 / sqrt(2 * 0.975 * 0.025).
        const SweepEstimate three = overSeeds({1.0, 2.0, 3.0});
        QCOMPARE(three.mean, 2.0);
        const double t2 = 0.95 / std::sqrt(2 * 0.975 * 0.025);
        QVERIFY(std::abs(three.high - (2.0 + t2 / std::sqrt(3.0))) < 1e-9);
        QVERIFY(std::abs(three.low - (2.0 - t2 / std::sqrt(3.0))) < 1e-9);
        // Near a bound the interval is taken on the log scale of the distance from it: inside,
        // not cut at the bound.
        const SweepEstimate bounded = overSeeds({1.0, 2.0, 3.0}, 1.5);
        QVERIFY(bounded.low > 1.5 && bounded.low < 2.0 && bounded.high > three.high);
        const SweepEstimate flat = overSeeds(std::vector<double>(100, 0.25));
        QCOMPARE(flat.low, 0.25);
        QCOMPARE(flat.high, 0.25);
        const SweepEstimate bad = overSeeds({1.0, std::nan("")});  // no NaN interval passes as one
        QVERIFY(std::isnan(bad.mean) && std::isnan(bad.low) && std::isnan(bad.high));
    }
};

QTEST_APPLESS_MAIN(TestAccuracyVsTime)
#include "test_accuracy_vs_time.moc"
