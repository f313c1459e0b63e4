// The accuracy-versus-time sweeps show their expected shape on the simulated rig, over three
// whole runs: one tap's calibrated belief means what it says on fresh taps; belief thresholds
// from 0.5 to 0.999 span one to several taps per decision, and more taps lower the perception
// error; coarser histograms and fewer samples cost accuracy; following trades robot time against
// path error, and accumulating evidence costs robot time.
#include <QtTest>

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
        for (const auto& r : runs_) {
            // On taps that neither trained the classifier nor fitted the calibration.
            const PerceptionSweepCalibration& c = r.sweeps.perceptionCalibration;
            QVERIFY(c.measured && c.calibrated && c.taps >= 1000);
            qInfo("seed %d: ECE %.3f raw, %.3f calibrated (%.3f if perfectly calibrated)",
                  int(r.spec.scene.seed), c.eceRaw, c.eceCalibrated, c.eceIfCalibrated);
            QVERIFY(c.eceRaw > 0.25);
            QVERIFY(c.eceCalibrated <= 0.05);
            // Evidence over repeated taps is worth less than a single tap's scaling says.
            QVERIFY(r.beliefCalibration.sequential.scale < r.beliefCalibration.scaling.scale);
        }
    }

    void thresholdsSpanDecisionTimesAndErrorsFall() {
        int significantFalls = 0;  // runs where both falls' intervals lie above 0
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
            // The errors fall below single taps', paired decision by decision; in most runs by
            // more than the fall's interval.
            qInfo(
                "seed %d: below single taps at 0.999: angle %.2f (%.2f-%.2f) deg, position "
                "%.3f (%.3f-%.3f) mm",
                int(r.spec.scene.seed), last.angleFall_deg.mean, last.angleFall_deg.low,
                last.angleFall_deg.high, last.positionFall_mm.mean, last.positionFall_mm.low,
                last.positionFall_mm.high);
            QVERIFY(last.angleFall_deg.mean > 0.0 && last.positionFall_mm.mean > 0.0);
            significantFalls += last.angleFall_deg.low > 0.0 && last.positionFall_mm.low > 0.0;
            // The paper's operating point on the same taps: one tap each.
            QCOMPARE(r.sweeps.perceptionSingleTap.meanTaps, 1.0);
            QCOMPARE(r.sweeps.perceptionSingleTap.angleFall_deg.mean, 0.0);
            // Plane and air are told apart from edges whatever the threshold.
            QVERIFY(first.planeDecisions > 0 && first.airDecisions > 0);
            QVERIFY(first.planeRecognised > 0.9 && first.airRecognised > 0.9);
        }
        QVERIFY(significantFalls >= 2);
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
};

QTEST_APPLESS_MAIN(TestAccuracyVsTime)
#include "test_accuracy_vs_time.moc"
