// The accuracy-versus-time sweeps show their expected shape on the simulated rig, over three
// whole runs: more taps per decision lower the perception error; coarser histograms and fewer
// samples cost accuracy; following trades robot time against path error.
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
        QVERIFY(cheaperComplete >= 2);
    }
};

QTEST_APPLESS_MAIN(TestAccuracyVsTime)
#include "test_accuracy_vs_time.moc"
