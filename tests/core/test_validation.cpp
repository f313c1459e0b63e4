// Offline validation (paper Figures 5, 6): the valid-range rule, and the shape of the result on
// the paper scene emerging from the physics, over several seeds.
#include <QtTest>

#include "core/run/ExperimentRun.h"
#include "core/validation/OfflineValidation.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

class TestValidation : public QObject {
    Q_OBJECT
private slots:
    void validRangeRule_data() {
        QTest::addColumn<QVector<double>>("angle");
        QTest::addColumn<QVector<double>>("position");
        QTest::addColumn<int>("first");
        QTest::newRow("clear minimum")
            << QVector<double>{90, 80, 60, 10, 0, 0, 0, 0, 20, 60}
            << QVector<double>{2, 2, 1, 0.5, 0.2, 0.2, 0.2, 0.2, 1, 2} << 5;
        QTest::newRow("flat: ties go to the edge")
            << QVector<double>(10, 0.0) << QVector<double>(10, 0.0)
            << 4;  // window 4..7, centre 5.5
        QTest::newRow("position breaks an angle tie")
            << QVector<double>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0}
            << QVector<double>{1, 1, 1, 1, 1, 1, 0, 0, 0, 0} << 7;
        QTest::newRow("minimum at the plane end")
            << QVector<double>{0, 0, 0, 0, 50, 50, 50, 50, 50, 50}
            << QVector<double>{0, 0, 0, 0, 1, 1, 1, 1, 1, 1} << 1;
    }
    void validRangeRule() {
        QFETCH(QVector<double>, angle);
        QFETCH(QVector<double>, position);
        QFETCH(int, first);
        const auto r = deriveValidRange(std::vector<double>(angle.begin(), angle.end()),
                                        std::vector<double>(position.begin(), position.end()), 4);
        QCOMPARE(r.first, first);
        QCOMPARE(r.last, first + 3);
    }

    void paperSceneHasThePapersShape() {
        // Over several whole runs (own data sets, training and valid range each): position errors
        // are smallest in a contiguous band around the edge, larger deep on the plane and toward
        // the air; angle errors are large on the plane and in the air, small in the band.
        const ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
            RunOptions options = test::onSimulatedRig();
            options.seed = seed;
            const RunResult r = runExperiment(spec, options);
            const auto& v = r.validation;
            const auto& vr = v.validRange;
            QVERIFY2(
                vr.first >= 5 && vr.last <= 14,
                qPrintable(
                    QString("seed %1: valid range %2-%3").arg(seed).arg(vr.first).arg(vr.last)));
            auto mean = [](const std::vector<double>& e, int a, int b) {
                double s = 0;
                for (int p = a; p <= b; ++p) s += e[p - 1];
                return s / (b - a + 1);
            };
            const double band = mean(v.positionMean, vr.first, vr.last);
            const double plane = mean(v.positionMean, 1, 3);
            const double towardAir = mean(v.positionMean, vr.last + 1, 18);
            QVERIFY2(
                band < 0.6 * plane,
                qPrintable(
                    QString("seed %1: band %2 mm vs plane %3 mm").arg(seed).arg(band).arg(plane)));
            QVERIFY2(band < 0.6 * towardAir,
                     qPrintable(QString("seed %1: band %2 mm vs air side %3 mm")
                                    .arg(seed)
                                    .arg(band)
                                    .arg(towardAir)));
            QVERIFY(mean(v.angleMean, vr.first, vr.last) < 20.0);
            QVERIFY(mean(v.angleMean, 1, 2) > 45.0);
            QVERIFY(mean(v.angleMean, 17, 18) > 45.0);
            // Each tap was classified once, into one of 72 classes.
            QCOMPARE(int(v.percepts.size()), 4 * 72);
            // One tap's raw posterior is overconfident; the fitted temperature (cross-fitted on
            // the held-out taps) brings its calibration error down by far.
            const BeliefCalibration& b = r.beliefCalibration;
            QVERIFY(b.measured && b.evaluationTaps == 4 * 72);
            qInfo("seed %d: ECE raw %.3f, scaled %.3f (factor %.4f; per-sample mean %.3f)",
                  int(seed), b.eceRaw, b.eceCalibrated, b.scaling.scale, b.ecePerSample);
            QVERIFY(b.eceRaw > 0.25);
            QVERIFY(b.eceCalibrated < 0.5 * b.eceRaw && b.eceCalibrated < 0.1);
            QVERIFY(b.scaling.scale > 0.0 && b.scaling.scale < 1.0);
            // On every validation tap the calibrated belief's top class is the classifier's
            // own decision, for the single-tap and the sequential scaling alike.
            std::vector<double> ll(72);
            for (const auto& t : r.taps) {
                if (spec.training.isTrainingSet(t.dataSet)) continue;
                r.classifier.logLikelihoods(t.record.tap, ll.data());
                const int decided = r.classifier.classify(t.record.tap);
                for (const BeliefScaling& sc : {b.scaling, b.sequential}) {
                    int top = -1;
                    const double p = calibratedTopBelief(ll.data(), 72, sc, &top);
                    QCOMPARE(top, decided);
                    QVERIFY(p > 0.0 && p <= 1.0);
                }
            }
        }
    }

    void theBeliefCalibrationIsMeasuredWhereItIsRead() {
        // A run over seeds keeps only its outcome: it measures the calibration only where its
        // trials or sweeps read it, and its training and validation stay those of a whole run.
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        spec.trials.clear();
        RunOptions whole = test::onSimulatedRig();
        whole.seed = 5;
        RunOptions outcomeOnly = whole;
        outcomeOnly.reportsBeliefCalibration = false;
        const RunResult reported = runExperiment(spec, whole);
        const RunResult unread = runExperiment(spec, outcomeOnly);
        QVERIFY(reported.beliefCalibration.measured);
        QVERIFY(!unread.beliefCalibration.measured);
        QCOMPARE(unread.validation.validRange.first, reported.validation.validRange.first);
        QCOMPARE(unread.validation.validRange.last, reported.validation.validRange.last);
        QVERIFY(unread.validation.positionMean == reported.validation.positionMean);
        // A sequential percept on the calibrated belief reads its sequential factor.
        spec.following.beliefThreshold = 0.9;
        const RunResult sequential = runExperiment(spec, outcomeOnly);
        QVERIFY(sequential.beliefCalibration.measured);
        QCOMPARE(sequential.beliefCalibration.sequential.scale,
                 reported.beliefCalibration.sequential.scale);
        // The naive belief does not.
        spec.following.calibratedBelief = false;
        QVERIFY(!runExperiment(spec, outcomeOnly).beliefCalibration.measured);
    }

    void cancellingKeepsTheTapsTaken() {
        const ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        // Asked to stop once the 100th tap is in.
        struct StopAt100 final : RunObserver {
            bool stop = false;
            void progressed(const RunProgress& p) override { stop = stop || p.tapsDone == 100; }
            bool stopRequested() const override { return stop; }
        } observer;
        RunOptions options = test::onSimulatedRig();
        options.observer = &observer;
        const RunResult r = runExperiment(spec, options);
        QVERIFY(r.cancelled);
        QCOMPARE(int(r.taps.size()), 100);
    }
};

QTEST_APPLESS_MAIN(TestValidation)
#include "test_validation.moc"
