#include "core/validation/OfflineValidation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "core/stats/Intervals.h"

namespace activetouch {

ValidRange deriveValidRange(const std::vector<double>& angle, const std::vector<double>& position,
                            int width) {
    const int n = static_cast<int>(angle.size());
    width = std::clamp(width, 1, std::max(1, n));
    const double amax = angle.empty() ? 0.0 : *std::max_element(angle.begin(), angle.end());
    const double pmax =
        position.empty() ? 0.0 : *std::max_element(position.begin(), position.end());
    auto norm = [](double v, double m) { return m > 0.0 ? v / m : 0.0; };
    const double edgeCentre = 0.5 * (n + 1);
    ValidRange best;
    double bestScore = std::numeric_limits<double>::infinity(), bestDistance = 0.0;
    for (int first = 1; first + width - 1 <= n; ++first) {
        double score = 0.0;
        for (int p = first; p < first + width; ++p)
            score += norm(angle[static_cast<std::size_t>(p - 1)], amax) +
                     norm(position[static_cast<std::size_t>(p - 1)], pmax);
        const double centreDistance = std::abs(first + 0.5 * (width - 1) - edgeCentre);
        const bool better = score < bestScore - 1e-12 || (std::abs(score - bestScore) <= 1e-12 &&
                                                          centreDistance < bestDistance - 1e-12);
        if (better) {
            bestScore = score;
            bestDistance = centreDistance;
            best = {first, first + width - 1, score};
        }
    }
    return best;
}

namespace {

/// Panels C, D of Figure 6: per position, the mean and standard deviation over orientations of
/// the per-class errors.
void errorsByPosition(const ClassSet& classes, ValidationResult& r) {
    const int O = static_cast<int>(classes.orientationsDeg.size());
    const int P = classes.positions;
    for (auto* series : {&r.angleMean, &r.angleStd, &r.positionMean, &r.positionStd})
        series->assign(static_cast<std::size_t>(P), 0.0);
    for (int p = 1; p <= P; ++p) {
        double sa = 0, sp = 0, qa = 0, qp = 0;
        for (int o = 0; o < O; ++o) {
            const auto& e = r.byClass[static_cast<std::size_t>(classes.classOf(o, p))];
            sa += e.angleError_deg;
            sp += e.positionError_mm;
            qa += e.angleError_deg * e.angleError_deg;
            qp += e.positionError_mm * e.positionError_mm;
        }
        const auto i = static_cast<std::size_t>(p - 1);
        r.angleMean[i] = sa / O;
        r.positionMean[i] = sp / O;
        r.angleStd[i] = std::sqrt(std::max(0.0, qa / O - r.angleMean[i] * r.angleMean[i]));
        r.positionStd[i] = std::sqrt(std::max(0.0, qp / O - r.positionMean[i] * r.positionMean[i]));
    }
}

/// The continuous percept's angle error on an edge tap, into its class; the error with the
/// class's position, or nothing where the percept is not an edge.
std::optional<std::pair<int, double>> continuousError(const HistogramClassifier& classifier,
                                                      const ClassSet& classes,
                                                      const CollectedTap& t, double temperature,
                                                      std::vector<double>& ll,
                                                      ValidationResult& r) {
    classifier.perceptScores(t.record.tap, ll.data());
    const Percept c =
        perceiveContinuous(classes, ll.data(), perceptTemperatureFor(temperature, t.record.tap));
    if (c.region != Region::Edge) return std::nullopt;
    const double err = angleDifferenceDeg(c.orientationDeg, classes.orientationDegOf(t.cls));
    auto& e = r.byClass[static_cast<std::size_t>(t.cls)];
    e.continuousAngleError_deg += err;
    ++e.continuousTaps;
    return std::pair{classes.positionOf(t.cls), err};
}

/// The continuous percept's median angle errors, over every edge tap and within the valid range.
void continuousMedians(const std::vector<std::pair<int, double>>& errors, ValidationResult& r) {
    r.continuousValidated = true;
    std::vector<double> all, inRange;
    for (const auto& [position, err] : errors) {
        all.push_back(err);
        if (position >= r.validRange.first && position <= r.validRange.last) inRange.push_back(err);
    }
    r.continuousMedianAngleError_deg = stats::medianOr(all, -1.0);
    r.continuousMedianAngleErrorInRange_deg = stats::medianOr(inRange, -1.0);
}

}  // namespace

ValidationResult validateOffline(const HistogramClassifier& classifier, const ClassSet& classes,
                                 const std::vector<const CollectedTap*>& testTaps,
                                 int validRangeWidth, double continuousTemperature) {
    const int C = classes.classCount();
    ValidationResult r;
    r.byClass.resize(static_cast<std::size_t>(C));
    r.confusion.assign(static_cast<std::size_t>(C * C), 0);
    for (int c = 0; c < C; ++c) {
        auto& e = r.byClass[static_cast<std::size_t>(c)];
        e.orientationIndex = classes.orientationIndexOf(c);
        e.position = classes.positionOf(c);
        e.region = classes.regionOf(c);
    }
    double angleSum = 0.0, positionSum = 0.0;
    int correct = 0;
    const bool continuous = continuousTemperature >= 0.0;
    std::vector<double> ll(continuous ? static_cast<std::size_t>(C) : 0);
    std::vector<std::pair<int, double>> continuousErrors;  // position, angle error
    for (const CollectedTap* t : testTaps) {
        if (continuous && classes.regionOf(t->cls) == Region::Edge)
            if (auto err = continuousError(classifier, classes, *t, continuousTemperature, ll, r))
                continuousErrors.push_back(*err);
        const Percept p = perceive(classifier, classes, t->record.tap);
        r.percepts.push_back(p);
        auto& e = r.byClass[static_cast<std::size_t>(t->cls)];
        const double angleErr =
            angleDifferenceDeg(p.orientationDeg, classes.orientationDegOf(t->cls));
        const double posErr = std::abs(p.offset_mm - t->trueOffset_mm);
        e.angleError_deg += angleErr;
        e.positionError_mm += posErr;
        e.correctFraction += (p.cls == t->cls);
        ++e.taps;
        angleSum += angleErr;
        positionSum += posErr;
        correct += (p.cls == t->cls);
        ++r.confusion[static_cast<std::size_t>(t->cls * C + p.cls)];
    }
    for (auto& e : r.byClass) {
        if (e.taps == 0) continue;
        e.angleError_deg /= e.taps;
        e.positionError_mm /= e.taps;
        e.correctFraction /= e.taps;
        if (e.continuousTaps > 0) e.continuousAngleError_deg /= e.continuousTaps;
    }
    const double n = std::max<std::size_t>(1, testTaps.size());
    r.angleError_deg = angleSum / n;
    r.positionError_mm = positionSum / n;
    r.correctFraction = correct / n;
    errorsByPosition(classes, r);
    r.validRange = deriveValidRange(r.angleMean, r.positionMean, validRangeWidth);
    if (continuous) continuousMedians(continuousErrors, r);
    return r;
}

}  // namespace activetouch
