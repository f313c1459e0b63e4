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
    // Times the temperature's reciprocal: a rounding apart from the quotient, far below the
    // single-precision exponential's own.
    const double inverse = 1.0 / temperature;
    for (int c = 0; c < n; ++c) {
        const double x = ll[c] * inverse - top;
        // In single precision (to about 2e-7 of each weight, at half the work): a weighted
        // mean's weights need no more.
        const double e = expNonPositiveOf<float>(static_cast<float>(x < -50.0 ? -50.0 : x));
        out[c] = x < -50.0 ? 0.0 : e;
    }
}

// The largest value over `temperature`: the same as the largest of the values each over it (a
// division by a positive number keeps their order). NaN where a value is NaN or +infinity.
ACTIVETOUCH_AVX2_CLONES double temperedTop(const double* ll, int n, double temperature) {
    double top = -std::numeric_limits<double>::infinity();
    int nan = 0;
    for (int c = 0; c < n; ++c) {
        top = ll[c] > top ? ll[c] : top;
        nan |= ll[c] != ll[c] ? 1 : 0;
    }
    if (top == std::numeric_limits<double>::infinity()) return top;
    if (nan != 0) return std::numeric_limits<double>::quiet_NaN();
    return top / temperature;
}

// 1 for a class that is an edge, 0 for one that is not (plane or air), worked out once per
// list of regions a thread sees (every class an edge where the list is empty).
const std::vector<double>& edgeMask(const ClassSet& classes) {
    thread_local std::vector<Region> seen;
    thread_local std::vector<double> mask;
    const auto n = static_cast<std::size_t>(classes.classCount());
    if (mask.size() != n || seen != classes.regions) {
        seen = classes.regions;
        mask.assign(n, 1.0);
        for (std::size_t c = 0; c < n && c < seen.size(); ++c)
            mask[c] = seen[c] == Region::Edge ? 1.0 : 0.0;
    }
    return mask;
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

// Each orientation's edge weight (its classes' weights, 0 off an edge) and its positions'
// weighted sum (class = orientation * positions + position - 1). Four orientations at a time, in
// running sums of their own, so that an addition need not wait for the last; each orientation's
// sums keep the order of its positions.
void orientationSums(const double* w, const double* isEdge, int n, int positions, double* weight,
                     double* positionSum) {
    int o = 0;
    for (; (o + 4) * positions <= n; o += 4) {
        double a[4] = {0.0, 0.0, 0.0, 0.0}, b[4] = {0.0, 0.0, 0.0, 0.0};
        for (int p = 0; p < positions; ++p)
            for (int j = 0; j < 4; ++j) {
                const int c = (o + j) * positions + p;
                const double wc = w[c] * isEdge[c];
                a[j] += wc;
                b[j] += wc * (p + 1);
            }
        for (int j = 0; j < 4; ++j) {
            weight[o + j] = a[j];
            positionSum[o + j] = b[j];
        }
    }
    for (; o * positions < n; ++o) {
        double a = 0.0, b = 0.0;
        for (int c = o * positions, p = 0; c < std::min(n, (o + 1) * positions); ++c, ++p) {
            const double wc = w[c] * isEdge[c];
            a += wc;
            b += wc * (p + 1);
        }
        weight[o] = a;
        positionSum[o] = b;
    }
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
    const double* isEdge = edgeMask(classes).data();
    const std::vector<Vec2>& normals = orientationNormals(classes.orientationsDeg);
    const int orientations = (n + positions - 1) / positions;
    thread_local std::vector<double> weightOf, positionSumOf;
    weightOf.assign(static_cast<std::size_t>(orientations), 0.0);
    positionSumOf.assign(static_cast<std::size_t>(orientations), 0.0);
    orientationSums(w, isEdge, n, positions, weightOf.data(), positionSumOf.data());
    for (int o = 0; o < orientations; ++o) {
        const double orientationWeight = weightOf[static_cast<std::size_t>(o)];
        const double positionSum = positionSumOf[static_cast<std::size_t>(o)];
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
