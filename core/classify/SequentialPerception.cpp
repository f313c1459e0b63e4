#include "core/classify/SequentialPerception.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace activetouch {

SequentialBelief::SequentialBelief(const ClassSet& classes) : classes_(classes) {
    const int C = classes.classCount();
    logPosterior_.assign(static_cast<std::size_t>(C), -std::log(static_cast<double>(C)));
    scratch_.resize(static_cast<std::size_t>(C));
}

void SequentialBelief::update(const double* ll) {
    const int C = static_cast<int>(logPosterior_.size());
    for (int c = 0; c < C; ++c) {
        // A class the evidence rules out (-inf) stays at -inf; NaN evidence counts as ruling out.
        const double v = ll[c];
        logPosterior_[static_cast<std::size_t>(c)] +=
            std::isnan(v) ? -std::numeric_limits<double>::infinity() : v;
    }
    double norm = logSumExp(logPosterior_.data(), C);
    if (!std::isfinite(norm)) {
        // Every class ruled out (or overflow): fall back to a flat belief rather than NaN.
        std::fill(logPosterior_.begin(), logPosterior_.end(), -std::log(static_cast<double>(C)));
        norm = 0.0;
    }
    for (double& v : logPosterior_) v -= norm;
    ++taps_;
}

void SequentialBelief::update(const HistogramClassifier& classifier, const Tap& tap) {
    classifier.logLikelihoods(tap, scratch_.data());
    update(scratch_.data());
}

void SequentialBelief::shift(Vec2 move) {
    const ClassSet& cs = classes_;
    const int P = cs.positions;
    std::vector<double> out(logPosterior_.size());
    for (std::size_t o = 0; o < cs.orientationsDeg.size(); ++o) {
        // Moving outward along the normal raises the offset, i.e. the position index.
        const int steps = static_cast<int>(std::lround(
            dot(move, directionFromDegrees(cs.orientationsDeg[o])) / cs.positionStep_mm));
        std::vector<double> mass(static_cast<std::size_t>(P), 0.0);
        for (int p = 1; p <= P; ++p) {
            const int to = std::clamp(p + steps, 1, P);
            mass[static_cast<std::size_t>(to - 1)] += std::exp(
                logPosterior_[static_cast<std::size_t>(cs.classOf(static_cast<int>(o), p))]);
        }
        for (int p = 1; p <= P; ++p)
            out[static_cast<std::size_t>(cs.classOf(static_cast<int>(o), p))] =
                std::log(mass[static_cast<std::size_t>(p - 1)]);
    }
    const double norm = logSumExp(out.data(), static_cast<int>(out.size()));
    for (double& v : out) v -= norm;
    logPosterior_ = out;
}

int SequentialBelief::best() const {
    return argmaxLowestIndex(logPosterior_.data(), static_cast<int>(logPosterior_.size()));
}

double SequentialBelief::bestPosterior() const {
    return std::exp(logPosterior_[static_cast<std::size_t>(best())]);
}

double SequentialBelief::perceptBelief() const {
    // The most likely class's percept: the class alone for an edge, every class of its region
    // for plane and air.
    const int top = best();
    const Region region = classes_.regionOf(top);
    if (region == Region::Edge) return bestPosterior();
    double mass = 0.0;
    for (std::size_t c = 0; c < logPosterior_.size(); ++c)
        if (classes_.regionOf(static_cast<int>(c)) == region) mass += std::exp(logPosterior_[c]);
    return std::min(1.0, mass);
}

double SequentialBelief::posterior(int cls) const {
    return std::exp(logPosterior_[static_cast<std::size_t>(cls)]);
}

}  // namespace activetouch
