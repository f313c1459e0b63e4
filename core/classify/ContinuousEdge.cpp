#include "core/classify/ContinuousEdge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/common/Avx2Clones.h"
#include "core/common/FastExp.h"
#include "core/geometry/Vec2.h"

namespace activetouch {

namespace {

// Each class's e^(ll / temperature - top), 0 where that is below e^-50 (a class ruled out reads
// -infinity and gets 0): several classes to an instruction, the same in either clone.
ACTIVETOUCH_AVX2_CLONES void edgeWeights(const double* ll, int n, double temperature, double top,
                                         double* out) {
    for (int c = 0; c < n; ++c) {
        const double x = ll[c] / temperature - top;
        const double e = expNonPositive(x);
        out[c] = x < -50.0 ? 0.0 : e;
    }
}

// The largest value over `temperature`: the same as the largest of the values each over it (a
// division by a positive number keeps their order). NaN where a value is NaN or +infinity.
ACTIVETOUCH_AVX2_CLONES double temperedTop(const double* ll, int n, double temperature) {
    double top = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < n; ++c) top = ll[c] > top ? ll[c] : top;
    if (top == std::numeric_limits<double>::infinity()) return top;
    for (int c = 0; c < n; ++c)
        if (std::isnan(ll[c])) return std::numeric_limits<double>::quiet_NaN();
    return top / temperature;
}

// The unit normal of each orientation, worked out once per list of orientations a thread sees.
const std::vector<Vec2>& orientationNormals(const std::vector<double>& degrees) {
    thread_local std::vector<double> seen;
    thread_local std::vector<Vec2> normals;
    if (seen != degrees) {
        seen = degrees;
        normals.clear();
        for (double d : degrees) {
            const double a = d * M_PI / 180.0;
            normals.push_back({std::cos(a), std::sin(a)});
        }
    }
    return normals;
}

// The weights' sum, in four running sums added in a fixed order.
ACTIVETOUCH_AVX2_CLONES double weightSum(const double* w, int n) {
    double sums[4] = {0.0, 0.0, 0.0, 0.0};
    int k = 0;
    for (; k + 4 <= n; k += 4)
        for (int j = 0; j < 4; ++j) sums[j] += w[k + j];
    for (; k < n; ++k) sums[0] += w[k];
    return (sums[0] + sums[1]) + (sums[2] + sums[3]);
}

}  // namespace

ContinuousEdge continuousEdge(const ClassSet& classes, const double* logLikelihoods,
                              double temperature) {
    ContinuousEdge percept;
    const int n = classes.classCount();
    if (n <= 0 || !logLikelihoods || !(temperature > 0.0) || !std::isfinite(temperature))
        return percept;
    // Normalised in the log domain (less the largest), so that sums of hundreds of
    // log-probabilities neither overflow nor all round to zero.
    const double top = temperedTop(logLikelihoods, n, temperature);
    if (!std::isfinite(top)) return percept;  // a NaN or +infinity, or every class ruled out
    thread_local std::vector<double> weight;
    weight.resize(static_cast<std::size_t>(n));
    // Terms e^-50 below the winner's carry no weight; a class ruled out reads -infinity, 0.
    const double* w = weight.data();
    edgeWeights(logLikelihoods, n, temperature, top, weight.data());
    // The winner's term is exp(0) = 1, so total >= 1: no division by zero.
    const double total = weightSum(w, n);
    // Each orientation's edge weight and its positions' weighted sum (class = orientation *
    // positions + position - 1), then its unit normal once; normalised by the total at the end.
    double edge = 0.0, sx = 0.0, sy = 0.0, sp = 0.0;
    const int positions = std::max(1, classes.positions);
    const bool allEdges = classes.regions.empty();
    const std::vector<Vec2>& normals = orientationNormals(classes.orientationsDeg);
    for (int c0 = 0, o = 0; c0 < n; c0 += positions, ++o) {
        double orientationWeight = 0.0, positionSum = 0.0;
        for (int c = c0, position = 1; c < std::min(n, c0 + positions); ++c, ++position) {
            const bool isEdge = allEdges || classes.regions[std::size_t(c)] == Region::Edge;
            const double wc = isEdge ? w[c] : 0.0;
            orientationWeight += wc;
            positionSum += wc * position;
        }
        if (orientationWeight <= 0.0) continue;
        edge += orientationWeight;
        sx += orientationWeight * normals[static_cast<std::size_t>(o)].x;
        sy += orientationWeight * normals[static_cast<std::size_t>(o)].y;
        sp += positionSum;
    }
    edge /= total;
    sx /= total;
    sy /= total;
    sp /= total;
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
