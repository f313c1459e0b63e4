// The histogram classifier's hard cases (docs/design.md §3): every degenerate input stays finite
// and decides exactly as an independent long-double implementation of eq. 1-2 does.
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

#include "core/classify/ContinuousEdge.h"
#include "core/classify/HistogramClassifier.h"
#include "core/common/Random.h"

using namespace activetouch;

namespace {

// An independent long-double implementation: dense sums over every sample, no count vector,
// no table layout; same binning rule (bins span each taxel's training min..max; outside values
// clamp; a constant taxel maps everything to bin 0) and, for a kernel, the same spreading rule
// (Gaussian weights to ceil(3 sigma) bins, cut at the range's ends, each count's in-range weights
// scaled to sum to 1), written as a dense sum over every pair of bins.
struct Reference {
    int C, K, B;
    long double alpha;
    std::vector<long double> lo, hi;
    std::vector<long double> counts;  // [c][k][b]
    std::vector<long double> totals;  // [c][k]

    Reference(const std::vector<std::pair<Tap, int>>& training, int classes, int bins,
              double smoothing, double kernelSigma = 0.0)
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
        if (kernelSigma > 0.0) spread(kernelSigma);
    }
    void spread(long double sigma) {
        const int reach = int(std::ceil(3.0L * sigma));
        const auto w = [&](int d) -> long double {
            return std::abs(d) > reach ? 0.0L : std::exp(-0.5L * d * d / (sigma * sigma));
        };
        std::vector<long double> inRange(B, 0);
        for (int src = 0; src < B; ++src)
            for (int dst = 0; dst < B; ++dst) inRange[src] += w(dst - src);
        for (int ck = 0; ck < C * K; ++ck) {
            const auto column = counts.begin() + std::ptrdiff_t(ck) * B;
            std::vector<long double> out(B, 0);
            for (int dst = 0; dst < B; ++dst)
                for (int src = 0; src < B; ++src)
                    out[dst] += column[src] * w(dst - src) / inRange[src];
            std::copy(out.begin(), out.end(), column);
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

HistogramClassifier trainOn(const Problem& p, int bins = 100, double smoothing = 0.01,
                            double kernelSigma = 0.0) {
    std::vector<LabelledTap> labelled;
    for (const auto& [tap, c] : p.training) labelled.push_back({&tap, c});
    return HistogramClassifier::train(labelled, p.classes, {bins, smoothing, kernelSigma});
}

// Every (taxel, class) likelihood sums to 1 over the bins: spreading lost no count.
void verifyNormalised(const HistogramClassifier& clf) {
    for (int k = 0; k < clf.taxelCount(); ++k)
        for (int c = 0; c < clf.classCount(); ++c) {
            double total = 0.0;
            for (int b = 0; b < clf.binCount(); ++b) {
                const double lp = clf.logProbability(k, b, c);
                QVERIFY2(std::isfinite(lp), "a log-probability is not finite");
                total += std::exp(lp);
            }
            QVERIFY2(std::abs(total - 1.0) < 1e-9,
                     qPrintable(QStringLiteral("taxel %1 class %2 sums to %3")
                                    .arg(k)
                                    .arg(c)
                                    .arg(total, 0, 'g', 17)));
        }
}

void verifyFiniteAndMatchesReference(const HistogramClassifier& clf, const Reference& ref,
                                     const Tap& tap) {
    std::vector<double> scores(clf.classCount());
    clf.logLikelihoods(tap, scores.data());
    for (double s : scores) QVERIFY2(std::isfinite(s), "a log-likelihood is not finite");
    QCOMPARE(clf.classify(tap), ref.decide(tap));
    // classify() and decide() screen classes in 16-bit fixed point: the same winner as the exact
    // scores, and the same posterior to far below any threshold's resolution.
    const int exactWinner = argmaxLowestIndex(scores.data(), clf.classCount());
    QCOMPARE(clf.classify(tap), exactWinner);
    const auto d = clf.decide(tap);
    QCOMPARE(d.cls, exactWinner);
    const double exactPosterior = std::exp(scores[static_cast<std::size_t>(exactWinner)] -
                                           logSumExp(scores.data(), clf.classCount()));
    QVERIFY2(std::abs(d.posterior - exactPosterior) <= 1e-12 * exactPosterior,
             qPrintable(
                 QString("%1 vs %2").arg(d.posterior, 0, 'g', 17).arg(exactPosterior, 0, 'g', 17)));
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
        // 32,760 samples: the longest taps the fixed-point screen sums, with counts in the
        // thousands; 10,000 per taxel is past it and summed exactly throughout.
        QTest::newRow("T = 2730") << 2730;
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

    void perceptScoresAreExactNearTheBestAndBoundedElsewhere() {
        // 648 classes, as general_shapes.json has: the continuous percept reads every class, the
        // ones near the best exactly and the rest from the 16-bit screen.
        const Problem p = makeProblem(648, 50, 12, 0.2, 37);
        const auto clf = trainOn(p);
        ClassSet classes;
        classes.orientationsDeg.clear();
        for (int o = 0; o < 36; ++o) classes.orientationsDeg.push_back(10.0 * o);
        classes.positions = 18;
        RandomStream r(41);
        std::vector<double> exact(648), read(648);
        int screened = 0;
        for (int i = 0; i < 20; ++i) {
            const Tap tap = randomTap(r, 50, 12, r.uniform(40, 160), 6.0);
            clf.logLikelihoods(tap, exact.data());
            clf.perceptScores(tap, read.data());
            const double best = *std::max_element(exact.begin(), exact.end());
            const double bound = clf.screeningBound(tap);
            QVERIFY(bound > 0.0 && bound < 1.0);
            for (std::size_t c = 0; c < exact.size(); ++c) {
                if (exact[c] >= best - HistogramClassifier::kPerceptMarginNats)
                    QCOMPARE(read[c], exact[c]);
                QVERIFY2(std::abs(read[c] - exact[c]) <= bound,
                         qPrintable(
                             QString("class %1: %2 against %3").arg(c).arg(read[c]).arg(exact[c])));
                screened += read[c] != exact[c];
            }
            // The percept at the default temperature (the tap's samples) moves by a small
            // fraction of a class: weights change by at most e^(bound / 50).
            const ContinuousEdge a = continuousEdge(classes, exact.data(), 50.0);
            const ContinuousEdge b = continuousEdge(classes, read.data(), 50.0);
            QCOMPARE(a.angleValid, b.angleValid);
            QVERIFY(std::abs(a.position - b.position) < 0.05);
            if (a.angleValid)
                QVERIFY(std::abs(std::remainder(a.angleDeg - b.angleDeg, 360.0)) < 0.5);
        }
        QVERIFY(screened > 0);  // the screen was read, not only the exact sums
    }

    void screeningKeepsDecisionsBetweenNearTwins() {
        // Classes trained on one tap, each with a single sample moved: their scores on a tap
        // like it differ by far less than the fixed-point screen resolves (about 0.1 nats
        // here), so the winner rests on the exact sums alone.
        RandomStream r(53);
        const Tap base = randomTap(r, 50, 12, 60.0, 6.0);
        Problem p{{}, 24};
        for (int c = 0; c < 24; ++c) {
            Tap t = base;
            t.at(c, c % 12) += 0.8;
            p.training.push_back({t, c});
        }
        const auto clf = trainOn(p);
        std::vector<double> scores(24);
        int within = 0;
        for (int i = 0; i < 200; ++i) {
            Tap t = base;
            for (double& v : t.samples) v += r.normal(0.0, 0.3);
            clf.logLikelihoods(t, scores.data());
            const int exact = argmaxLowestIndex(scores.data(), 24);
            QCOMPARE(clf.classify(t), exact);
            QCOMPARE(clf.decide(t).cls, exact);
            std::vector<double> sorted = scores;
            std::sort(sorted.rbegin(), sorted.rend());
            if (sorted[0] - sorted[1] < 1e-3) ++within;
        }
        qInfo("%d of 200 taps with the best two classes within 0.001 nats", within);
        QVERIFY(within > 20);  // the case this test is for does occur
    }

    void screenSumsAgreeBetweenTheVectorAndPortableKernels() {
        // Every class count from 1 to 100 (rows padded to 16), odd and even row counts, extreme
        // levels and counts: the AVX2 kernel's pairwise sums equal the plain loop's.
        RandomStream r(61);
        for (int classes = 1; classes <= 100; ++classes) {
            const std::size_t stride = (static_cast<std::size_t>(classes) + 15) / 16 * 16;
            const std::size_t tableRows = 40;
            std::vector<std::int16_t, CacheLineAllocator<std::int16_t>> table(
                (tableRows + 1) * stride, 0);
            for (std::size_t row = 0; row < tableRows; ++row)
                for (std::size_t c = 0; c < static_cast<std::size_t>(classes); ++c)
                    table[row * stride + c] =
                        r.uniform(0, 1) < 0.1
                            ? static_cast<std::int16_t>(r.uniform(0, 1) < 0.5 ? -32767 : 32767)
                            : static_cast<std::int16_t>(std::lround(r.uniform(-32767, 32767)));
            const std::size_t rows = 1 + static_cast<std::size_t>(classes) % 37;
            std::vector<std::uint32_t> cells(rows + 1);
            // The count past the last row partners the zero row: any value must do.
            std::vector<std::int32_t> counts(rows + 1, 31000);
            for (std::size_t i = 0; i < rows; ++i) {
                cells[i] = static_cast<std::uint32_t>(i);
                // At most 32,767 samples in all, as in a tap the screen takes.
                counts[i] = i == 0 ? 20000 : static_cast<std::int32_t>(r.uniform(1, 300));
            }
            cells[rows] = static_cast<std::uint32_t>(tableRows);
            std::vector<std::int32_t> vectorSums(stride), portableSums(stride);
            detail::screenSums(table.data(), stride, cells.data(), counts.data(), rows,
                               vectorSums.data(), false);
            detail::screenSums(table.data(), stride, cells.data(), counts.data(), rows,
                               portableSums.data(), true);
            for (std::size_t c = 0; c < stride; ++c) {
                std::int64_t exact = 0;
                for (std::size_t i = 0; i < rows; ++i)
                    exact += std::int64_t{counts[i]} * table[cells[i] * stride + c];
                QCOMPARE(static_cast<std::int64_t>(portableSums[c]), exact);
                QCOMPARE(vectorSums[c], portableSums[c]);
            }
        }
    }

    void countCellsForgetALargerTablesCells() {
        // A tap of a larger table (five groups of 32 cells) counted first, then one of a small
        // table (one group) on the same thread: none of the first tap's cells comes back, on the
        // vector path (whose marks are padded to whole words) or the portable one.
        for (const bool portable : {false, true}) {
            std::vector<std::uint32_t> big{0, 40, 100, 150}, small{3, 5, 5}, cells(256);
            std::vector<std::int32_t> counts(256);
            detail::countCells(big.data(), big.size(), 160, cells.data(), counts.data(), portable);
            const std::size_t n = detail::countCells(small.data(), small.size(), 24, cells.data(),
                                                     counts.data(), portable);
            QCOMPARE(n, std::size_t(2));
            QCOMPARE(cells[0], 3u);
            QCOMPARE(cells[1], 5u);
            QCOMPARE(counts[1], 2);
        }
    }

    void countCellsAgreeBetweenTheVectorAndPortableReadings() {
        // Tables of every size around the counters' groups, sparse and dense taps, the last cell,
        // and counts whose low 8 or 16 bits are zero (65,536 and 256 samples in one cell): both
        // readings give every touched cell once, ascending, with its count, and leave nothing
        // behind for the next tap.
        RandomStream r(67);
        for (const std::size_t cellsTotal :
             {std::size_t{1}, std::size_t{15}, std::size_t{16}, std::size_t{17}, std::size_t{31},
              std::size_t{32}, std::size_t{33}, std::size_t{1200}, std::size_t{5000}}) {
            for (const bool portable : {false, true}) {
                for (int round = 0; round < 3; ++round) {
                    std::vector<std::uint32_t> cellOf;
                    const auto draws = static_cast<std::size_t>(r.uniform(1, 800));
                    for (std::size_t i = 0; i < draws; ++i)
                        cellOf.push_back(static_cast<std::uint32_t>(
                            std::min(cellsTotal - 1,
                                     static_cast<std::size_t>(r.uniform(0, double(cellsTotal))))));
                    cellOf.push_back(static_cast<std::uint32_t>(cellsTotal - 1));
                    if (round == 1) cellOf.insert(cellOf.end(), 65536, 0u);
                    if (round == 2)
                        cellOf.insert(cellOf.end(), 256,
                                      static_cast<std::uint32_t>(cellsTotal / 2));
                    std::map<std::uint32_t, std::int32_t> expected;
                    for (const std::uint32_t cell : cellOf) ++expected[cell];
                    const std::size_t room =
                        std::min(cellOf.size(), cellsTotal) + detail::kCountCellsSlack;
                    std::vector<std::uint32_t> cells(room);
                    std::vector<std::int32_t> counts(room);
                    const std::size_t distinct =
                        detail::countCells(cellOf.data(), cellOf.size(), cellsTotal, cells.data(),
                                           counts.data(), portable);
                    QCOMPARE(distinct, expected.size());
                    std::size_t i = 0;
                    for (const auto& [cell, count] : expected) {
                        QCOMPARE(cells[i], cell);
                        QCOMPARE(counts[i], count);
                        ++i;
                    }
                }
            }
        }
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

    void kernelDecisionsMatchLongDoubleReference_data() {
        QTest::addColumn<double>("sigma");
        QTest::newRow("sigma 0 (the paper's histogram)") << 0.0;
        QTest::newRow("sigma 0.1 (reach 1 bin)") << 0.1;
        QTest::newRow("sigma 2.5") << 2.5;
        QTest::newRow("sigma 50 (reach wider than the range)") << 50.0;
    }
    void kernelDecisionsMatchLongDoubleReference() {
        QFETCH(double, sigma);
        const Problem p = makeProblem(72, 50, 12, 1.5, 53);
        const auto clf = trainOn(p, 100, 0.01, sigma);
        const Reference ref(p.training, p.classes, 100, 0.01, sigma);
        verifyNormalised(clf);
        RandomStream r(59);
        for (int i = 0; i < 40; ++i)
            verifyFiniteAndMatchesReference(clf, ref,
                                            randomTap(r, 50, 12, r.uniform(30, 150), 6.0));
    }

    void kernelSpreadsEachCountOverItsNeighboursOnly() {
        // One taxel, range 0..100 in 100 bins of 1: class 0 holds one count in each end bin,
        // class 1 two counts in bin 50.
        Problem p{{}, 2};
        Tap ends(2, 1), middle(2, 1);
        ends.at(0, 0) = 0.0;
        ends.at(1, 0) = 100.0;
        middle.at(0, 0) = middle.at(1, 0) = 50.5;
        p.training = {{ends, 0}, {middle, 1}};
        const double sigma = 2.0, alpha = 0.01;
        const auto clf = trainOn(p, 100, alpha, sigma);
        QCOMPARE(clf.binOf(0, 50.5), 50);
        const auto w = [&](int d) { return std::exp(-0.5 * d * d / (sigma * sigma)); };
        double full = 0.0, half = 0.0;  // in-range weight of a middle bin and of an end bin
        for (int d = -6; d <= 6; ++d) full += w(d);
        for (int d = 0; d <= 6; ++d) half += w(d);
        const double denominator = 2.0 + 100 * alpha;
        for (int d = 0; d <= 8; ++d) {
            const double expected = (d <= 6 ? 2.0 * w(d) / full : 0.0) + alpha;
            QVERIFY(std::abs(clf.logProbability(0, 50 + d, 1) - std::log(expected / denominator)) <
                    1e-12);
            QCOMPARE(clf.logProbability(0, 50 - d, 1), clf.logProbability(0, 50 + d, 1));
        }
        // A count in an end bin keeps its whole weight inside the range.
        QVERIFY(std::abs(clf.logProbability(0, 0, 0) -
                         std::log((1.0 / half + alpha) / denominator)) < 1e-12);
        QVERIFY(std::abs(clf.logProbability(0, 99, 0) -
                         std::log((1.0 / half + alpha) / denominator)) < 1e-12);
        verifyNormalised(clf);
    }

    void kernelGivesUnseenNeighbouringBinsToTheNearestClass() {
        // A tap three bins from where class 1 was trained and far from class 0: the raw histogram
        // has seen neither class there, scores both at the smoothing floor and ties to class 0;
        // the kernel gives it to class 1.
        Problem p{{}, 2};
        Tap zero(50, 1), one(50, 1), probe(50, 1);
        for (int s = 0; s < 50; ++s) {
            zero.at(s, 0) = s == 0 ? 0.0 : s == 1 ? 100.0 : 20.5;
            one.at(s, 0) = 60.5;
            probe.at(s, 0) = 63.5;
        }
        p.training = {{zero, 0}, {one, 1}};
        QCOMPARE(trainOn(p, 100, 0.01, 0.0).classify(probe), 0);
        QCOMPARE(trainOn(p, 100, 0.01, 2.5).classify(probe), 1);
        // Beyond the kernel's reach (ceil(3 sigma) bins: 2 for sigma 0.6, 3 for 0.9) it is unseen
        // again.
        QCOMPARE(trainOn(p, 100, 0.01, 0.6).classify(probe), 0);
        QCOMPARE(trainOn(p, 100, 0.01, 0.9).classify(probe), 1);
    }

    void kernelOnDegenerateRanges_data() {
        QTest::addColumn<int>("bins");
        QTest::addColumn<double>("sigma");
        QTest::newRow("one bin") << 1 << 2.5;
        QTest::newRow("two bins, sigma 50") << 2 << 50.0;
        QTest::newRow("100 bins, sigma 50") << 100 << 50.0;
        QTest::newRow("100000 bins, sigma 0.3") << 100000 << 0.3;
    }
    void kernelOnDegenerateRanges() {
        QFETCH(int, bins);
        QFETCH(double, sigma);
        Problem p = makeProblem(6, 20, 12, 8.0, 61);
        for (auto& [tap, c] : p.training)
            for (int s = 0; s < tap.sampleCount(); ++s) tap.at(s, 7) = 12.0;  // a constant taxel
        const auto clf = trainOn(p, bins, 0.01, sigma);
        verifyNormalised(clf);
        if (bins == 1)
            for (int k = 0; k < 12; ++k)
                for (int c = 0; c < 6; ++c) QCOMPARE(clf.logProbability(k, 0, c), 0.0);
        RandomStream r(67);
        Tap t = randomTap(r, 20, 12, 60.0, 6.0);
        const int before = clf.classify(t);
        for (double v : {0.0, 12.0, 255.0}) {
            for (int s = 0; s < 20; ++s) t.at(s, 7) = v;
            QCOMPARE(clf.classify(t), before);
        }
        if (bins <= 100) {
            const Reference ref(p.training, p.classes, bins, 0.01, sigma);
            verifyFiniteAndMatchesReference(clf, ref, t);
        }
    }

    void badKernelsAreRefused_data() {
        QTest::addColumn<double>("sigma");
        QTest::newRow("negative") << -1.0;
        QTest::newRow("NaN") << qQNaN();
        QTest::newRow("infinite") << qInf();
        QTest::newRow("wider than 50 bins") << 50.5;
    }
    void badKernelsAreRefused() {
        QFETCH(double, sigma);
        const ClassifierSettings settings{100, 0.01, sigma};
        QVERIFY(QString::fromStdString(settings.problem()).contains("kernel_sigma_bins"));
        const Problem p = makeProblem(4, 50, 12, 10.0, 71);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, trainOn(p, 100, 0.01, sigma));
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
