// The histogram classifier's hard cases (DESIGN.md §2): every degenerate input stays finite and
// decides exactly as an independent long-double implementation of eq. 1-2 does.
#include <QtTest>
#include <cmath>
#include <limits>

#include "core/classify/HistogramClassifier.h"
#include "core/common/Random.h"

using namespace activetouch;

namespace {

// An independent long-double implementation: dense sums over every sample, no count vector,
// no table layout; same binning rule (bins span each taxel's training min..max; outside values
// clamp; a constant taxel maps everything to bin 0).
struct Reference {
    int C, K, B;
    long double alpha;
    std::vector<long double> lo, hi;
    std::vector<long double> counts;  // [c][k][b]
    std::vector<long double> totals;  // [c][k]

    Reference(const std::vector<std::pair<Tap, int>>& training, int classes, int bins,
              double smoothing)
        : C(classes), K(training.front().first.taxels), B(bins), alpha(smoothing) {
        lo.assign(K, std::numeric_limits<long double>::infinity());
        hi.assign(K, -std::numeric_limits<long double>::infinity());
        for (const auto& [tap, c] : training)
            for (int t = 0; t < tap.sampleCount(); ++t)
                for (int k = 0; k < K; ++k) {
                    lo[k] = std::min<long double>(lo[k], tap.at(t, k));
                    hi[k] = std::max<long double>(hi[k], tap.at(t, k));
                }
        counts.assign(std::size_t(C) * K * B, 0);
        totals.assign(std::size_t(C) * K, 0);
        for (const auto& [tap, c] : training)
            for (int t = 0; t < tap.sampleCount(); ++t)
                for (int k = 0; k < K; ++k) {
                    counts[(std::size_t(c) * K + k) * B + bin(k, tap.at(t, k))] += 1;
                    totals[std::size_t(c) * K + k] += 1;
                }
    }
    int bin(int k, double v) const {
        const double width = double(hi[k] - lo[k]);
        if (!(width > 0)) return 0;
        if (!(v > double(lo[k]))) return 0;
        if (!(v < double(hi[k]))) return B - 1;
        return std::min(B - 1, int((v - double(lo[k])) * (B / width)));
    }
    std::vector<long double> scores(const Tap& tap) const {
        std::vector<long double> s(C, 0);
        for (int c = 0; c < C; ++c)
            for (int k = 0; k < K; ++k)
                for (int t = 0; t < tap.sampleCount(); ++t) {
                    const long double p =
                        (counts[(std::size_t(c) * K + k) * B + bin(k, tap.at(t, k))] + alpha) /
                        (totals[std::size_t(c) * K + k] + B * alpha);
                    s[c] += std::log(p);
                }
        return s;
    }
    int decide(const Tap& tap) const {
        // Lowest class among those within the tie tolerance of the maximum.
        const auto s = scores(tap);
        const long double m = *std::max_element(s.begin(), s.end());
        const long double floor =
            m - (long double)kTieTolerance * std::max<long double>(1.0L, std::abs(m));
        for (int c = 0; c < C; ++c)
            if (s[c] >= floor) return c;
        return 0;
    }
};

Tap randomTap(RandomStream& r, int T, int K, double centre, double spread) {
    Tap t(T, K);
    for (int s = 0; s < T; ++s)
        for (int k = 0; k < K; ++k)
            t.at(s, k) = std::clamp(r.normal(centre + 7.0 * k, spread), 0.0, 255.0);
    return t;
}

struct Problem {
    std::vector<std::pair<Tap, int>> training;
    int classes;
};

// Classes differ in their mean pressure; `separation` 0 makes them near-identical.
Problem makeProblem(int classes, int T, int K, double separation, std::uint64_t seed) {
    RandomStream r(seed);
    Problem p{{}, classes};
    for (int c = 0; c < classes; ++c)
        p.training.push_back({randomTap(r, T, K, 40.0 + separation * c, 6.0), c});
    return p;
}

HistogramClassifier trainOn(const Problem& p, int bins = 100, double smoothing = 0.01) {
    std::vector<LabelledTap> labelled;
    for (const auto& [tap, c] : p.training) labelled.push_back({&tap, c});
    return HistogramClassifier::train(labelled, p.classes, {bins, smoothing});
}

void verifyFiniteAndMatchesReference(const HistogramClassifier& clf, const Reference& ref,
                                     const Tap& tap) {
    std::vector<double> scores(clf.classCount());
    clf.logLikelihoods(tap, scores.data());
    for (double s : scores) QVERIFY2(std::isfinite(s), "a log-likelihood is not finite");
    QCOMPARE(clf.classify(tap), ref.decide(tap));
    const auto d = clf.decide(tap);
    QVERIFY(std::isfinite(d.posterior) && d.posterior > 0.0 && d.posterior <= 1.0);
    // The fast sum equals the dense long-double sum to rounding.
    const auto refScores = ref.scores(tap);
    for (int c = 0; c < clf.classCount(); ++c)
        QVERIFY(std::abs(double(refScores[c]) - scores[c]) <=
                1e-9 * std::max(1.0, std::abs(scores[c])));
}

}  // namespace

class TestClassifier : public QObject {
    Q_OBJECT
private slots:
    void decisionsMatchLongDoubleReference() {
        const Problem p = makeProblem(72, 50, 12, 1.5, 7);
        const auto clf = trainOn(p);
        const Reference ref(p.training, p.classes, 100, 0.01);
        RandomStream r(99);
        for (int i = 0; i < 200; ++i)
            verifyFiniteAndMatchesReference(clf, ref,
                                            randomTap(r, 50, 12, r.uniform(30, 150), 6.0));
    }

    void zeroCountBinsStayFinite() {
        // Training occupies a narrow band; test samples land in bins no class ever saw.
        Problem p = makeProblem(4, 50, 12, 20.0, 3);
        p.training.push_back({Tap(1, 12), 0});
        for (double& v : p.training.back().first.samples) v = 200.0;  // widen the range
        const auto clf = trainOn(p);
        const Reference ref(p.training, p.classes, 100, 0.01);
        Tap t(50, 12);
        for (double& v : t.samples) v = 170.0;  // empty bins for every class
        verifyFiniteAndMatchesReference(clf, ref, t);
    }

    void samplesOutsideTrainedRangeClampToEndBins() {
        const Problem p = makeProblem(6, 50, 12, 10.0, 5);
        const auto clf = trainOn(p);
        const Reference ref(p.training, p.classes, 100, 0.01);
        Tap below(50, 12), above(50, 12), atMin(50, 12), atMax(50, 12);
        for (int s = 0; s < 50; ++s)
            for (int k = 0; k < 12; ++k) {
                below.at(s, k) = clf.rangeMin(k) - 1000.0;
                above.at(s, k) = clf.rangeMax(k) + 1e6;
                atMin.at(s, k) = clf.rangeMin(k);
                atMax.at(s, k) = clf.rangeMax(k);
            }
        verifyFiniteAndMatchesReference(clf, ref, below);
        verifyFiniteAndMatchesReference(clf, ref, above);
        std::vector<double> a(6), b(6);
        clf.logLikelihoods(below, a.data());
        clf.logLikelihoods(atMin, b.data());
        for (int c = 0; c < 6; ++c) QCOMPARE(a[c], b[c]);
        clf.logLikelihoods(above, a.data());
        clf.logLikelihoods(atMax, b.data());
        for (int c = 0; c < 6; ++c) QCOMPARE(a[c], b[c]);
    }

    void constantTaxelInTrainingNeverDividesByZero() {
        Problem p = makeProblem(8, 50, 12, 8.0, 11);
        for (auto& [tap, c] : p.training)
            for (int s = 0; s < tap.sampleCount(); ++s) tap.at(s, 4) = 0.0;  // taxel 4 never varied
        const auto clf = trainOn(p);
        const Reference ref(p.training, p.classes, 100, 0.01);
        RandomStream r(4);
        Tap t = randomTap(r, 50, 12, 60.0, 6.0);
        verifyFiniteAndMatchesReference(clf, ref, t);
        // Whatever the constant taxel reads now, it cannot sway the decision.
        const int before = clf.classify(t);
        for (double v : {0.0, 3.0, 255.0, -5.0}) {
            for (int s = 0; s < 50; ++s) t.at(s, 4) = v;
            QCOMPARE(clf.classify(t), before);
            verifyFiniteAndMatchesReference(clf, ref, t);
        }
    }

    void saturatedAndAllZeroTaps() {
        const Problem p = makeProblem(72, 50, 12, 2.0, 13);
        const auto clf = trainOn(p);
        const Reference ref(p.training, p.classes, 100, 0.01);
        Tap zero(50, 12), saturated(50, 12);
        for (double& v : saturated.samples) v = 255.0;
        verifyFiniteAndMatchesReference(clf, ref, zero);
        verifyFiniteAndMatchesReference(clf, ref, saturated);
    }

    void exactTiesBreakToLowestClass() {
        // Classes 2, 5 and 6 are trained on the very same tap: any tap scores them identically.
        RandomStream r(17);
        Problem p{{}, 8};
        const Tap shared = randomTap(r, 50, 12, 80.0, 5.0);
        for (int c = 0; c < 8; ++c)
            p.training.push_back(
                {(c == 2 || c == 5 || c == 6) ? shared : randomTap(r, 50, 12, 20.0 + 25 * c, 5.0),
                 c});
        const auto clf = trainOn(p);
        std::vector<double> scores(8);
        clf.logLikelihoods(shared, scores.data());
        QCOMPARE(scores[2], scores[5]);
        QCOMPARE(scores[2], scores[6]);
        QCOMPARE(clf.classify(shared), 2);
        // Order of samples does not matter either.
        Tap reversed = shared;
        for (int s = 0; s < 25; ++s)
            for (int k = 0; k < 12; ++k) std::swap(reversed.at(s, k), reversed.at(49 - s, k));
        QCOMPARE(clf.classify(reversed), 2);
        // argmax itself: lowest index among equals, NaN never wins.
        const double v[] = {qQNaN(), 1.0, 3.0, 3.0, -qInf()};
        QCOMPARE(argmaxLowestIndex(v, 5), 2);
        // Sums equal but for rounding in the last bits are a tie too.
        const double w[] = {-1000.0, -1000.0 + 1e-12, -1000.1};
        QCOMPARE(argmaxLowestIndex(w, 3), 0);
        const double x[] = {-1000.0, -999.0};
        QCOMPARE(argmaxLowestIndex(x, 2), 1);
    }

    void singleSampleAndTenThousandSampleTaps_data() {
        QTest::addColumn<int>("samples");
        QTest::newRow("T = 1") << 1;
        QTest::newRow("T = 10000") << 10000;
    }
    void singleSampleAndTenThousandSampleTaps() {
        QFETCH(int, samples);
        const Problem p = makeProblem(72, samples, 12, 1.0, 19);
        const auto clf = trainOn(p);
        const Reference ref(p.training, p.classes, 100, 0.01);
        RandomStream r(23);
        for (int i = 0; i < 5; ++i)
            verifyFiniteAndMatchesReference(clf, ref,
                                            randomTap(r, samples, 12, r.uniform(40, 110), 6.0));
    }

    void sixHundredFortyEightClasses() {
        // 36 orientations x 18 positions.
        const Problem p = makeProblem(648, 50, 12, 0.2, 29);
        const auto clf = trainOn(p);
        QCOMPARE(clf.classCount(), 648);
        const Reference ref(p.training, p.classes, 100, 0.01);
        RandomStream r(31);
        for (int i = 0; i < 10; ++i)
            verifyFiniteAndMatchesReference(clf, ref,
                                            randomTap(r, 50, 12, r.uniform(40, 160), 6.0));
    }

    void nearUniformLikelihood() {
        // Every class trained on almost the same data, large smoothing: the posterior is close to
        // uniform and must still be finite and normalised.
        const Problem p = makeProblem(72, 50, 12, 1e-6, 37);
        std::vector<LabelledTap> labelled;
        for (const auto& [tap, c] : p.training) labelled.push_back({&tap, c});
        const auto clf = HistogramClassifier::train(labelled, 72, {100, 1000.0});
        const Reference ref(p.training, 72, 100, 1000.0);
        RandomStream r(41);
        const Tap t = randomTap(r, 50, 12, 40.0, 6.0);
        verifyFiniteAndMatchesReference(clf, ref, t);
        std::vector<double> scores(72);
        clf.logLikelihoods(t, scores.data());
        const double lse = logSumExp(scores.data(), 72);
        double total = 0.0;
        for (double s : scores) total += std::exp(s - lse);
        QVERIFY(std::abs(total - 1.0) < 1e-12);
        QVERIFY(clf.decide(t).posterior < 0.05);
    }

    void nonFiniteSamplesAreBinnedDeterministically() {
        const Problem p = makeProblem(4, 50, 12, 10.0, 43);
        const auto clf = trainOn(p);
        Tap t(50, 12);
        t.at(0, 0) = qQNaN();
        t.at(1, 1) = qInf();
        t.at(2, 2) = -qInf();
        std::vector<double> scores(4);
        clf.logLikelihoods(t, scores.data());
        for (double s : scores) QVERIFY(std::isfinite(s));
        QCOMPARE(clf.binOf(0, qQNaN()), 0);
        QCOMPARE(clf.binOf(1, qInf()), 99);
    }

    void badSettingsAndTrainingSetsAreRefused() {
        const Problem p = makeProblem(4, 50, 12, 10.0, 47);
        std::vector<LabelledTap> labelled;
        for (const auto& [tap, c] : p.training) labelled.push_back({&tap, c});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 HistogramClassifier::train(labelled, 4, {100, 0.0}));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 HistogramClassifier::train(labelled, 4, {0, 0.01}));
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            HistogramClassifier::train(labelled, 5, {100, 0.01}));  // class 4 unseen
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 HistogramClassifier::train({}, 4, {100, 0.01}));
        Tap bad = p.training[0].first;
        bad.at(3, 3) = qQNaN();
        labelled[0].tap = &bad;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 HistogramClassifier::train(labelled, 4, {100, 0.01}));
    }

    void logSumExpIsStable() {
        const double big[] = {1e308, 1e308};
        QCOMPARE(logSumExp(big, 2), 1e308 + std::log(2.0));
        const double small[] = {-1e6, -1e6 - 1.0};
        QVERIFY(std::isfinite(logSumExp(small, 2)));
        QVERIFY(std::abs(logSumExp(small, 2) - (-1e6 + std::log1p(std::exp(-1.0)))) < 1e-6);
    }
};

QTEST_APPLESS_MAIN(TestClassifier)
#include "test_classifier.moc"
