#include "core/classify/ContinuousEdge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace activetouch {

ContinuousEdge continuousEdge(const ClassSet& classes, const double* logLikelihoods,
                              double temperature) {
    ContinuousEdge percept;
    const int n = classes.classCount();
    if (n <= 0 || !logLikelihoods || !(temperature > 0.0) || !std::isfinite(temperature))
        return percept;
    // Normalise in the log domain (log-sum-exp), so that sums of hundreds of log-probabilities
    // neither overflow nor all round to zero.
    double top = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < n; ++c) {
        const double v = logLikelihoods[c];
        if (std::isnan(v) || v == std::numeric_limits<double>::infinity()) return percept;
        top = std::max(top, v / temperature);
    }
    if (!std::isfinite(top)) return percept;  // every class ruled out
    std::vector<double> weight(static_cast<std::size_t>(n));
    double total = 0.0;
    for (int c = 0; c < n; ++c) {
        // Terms e^-50 below the winner's change no sum a double holds beside it: skip the exp.
        const double x = logLikelihoods[c] / temperature - top;
        weight[std::size_t(c)] = x < -50.0 ? 0.0 : std::exp(x);
        total += weight[std::size_t(c)];
    }
    // Each orientation's unit normal, once: many classes share it.
    std::vector<double> normalX(classes.orientationsDeg.size()), normalY(normalX.size());
    for (std::size_t o = 0; o < normalX.size(); ++o) {
        const double a = classes.orientationsDeg[o] * M_PI / 180.0;
        normalX[o] = std::cos(a);
        normalY[o] = std::sin(a);
    }
    // The winner's term is exp(0) = 1, so total >= 1: no division by zero.
    double edge = 0.0, sx = 0.0, sy = 0.0, sp = 0.0;
    for (int c = 0; c < n; ++c) {
        const double w = weight[std::size_t(c)] / total;
        if (classes.regionOf(c) != Region::Edge || w <= 0.0) continue;
        const auto o = static_cast<std::size_t>(classes.orientationIndexOf(c));
        edge += w;
        sx += w * normalX[o];
        sy += w * normalY[o];
        sp += w * classes.positionOf(c);
    }
    percept.edgeWeight = std::clamp(edge, 0.0, 1.0);
    if (edge <= 0.0) return percept;
    percept.positionValid = true;
    percept.position = sp / edge;
    const double resultant = std::hypot(sx, sy) / edge;
    percept.concentration = std::clamp(resultant, 0.0, 1.0);
    // Below this the normals cancel: rounding, not the posterior, would choose the angle.
    constexpr double kNoMeanAngle = 1e-9;
    if (resultant <= kNoMeanAngle) return percept;
    percept.angleValid = true;
    double degrees = std::atan2(sy, sx) * 180.0 / M_PI;
    if (degrees < 0.0) degrees += 360.0;
    percept.angleDeg = degrees >= 360.0 ? 0.0 : degrees;
    return percept;
}

}  // namespace activetouch
