#pragma once
// Sequential Bayesian perception (the paper's stated future work, after Lepora et al.'s active
// Bayesian perception): evidence from successive taps accumulates into a belief over the classes
// until the largest posterior crosses a belief threshold. Always in the log domain; posteriors
// are normalised with log-sum-exp after every update, so they sum to one and never hold NaN.
// Between taps the fingertip may move (repositioning): the belief over positions then shifts with
// it, so the evidence already gathered keeps describing where the tip now is.
#include <vector>

#include "core/classify/HistogramClassifier.h"
#include "core/tap/ClassSet.h"

namespace activetouch {

class SequentialBelief {
public:
    SequentialBelief() = default;
    /// A flat prior over `classes`.
    explicit SequentialBelief(const ClassSet& classes);

    /// Adds one tap's log-likelihoods (classCount values) and renormalises.
    void update(const double* logLikelihoods);
    /// Adds one tap's evidence as the classifier reads it.
    void update(const HistogramClassifier& classifier, const Tap& tap);

    /// The tip moved by `move` (mm): every orientation's positions shift by the move's component
    /// along that orientation's outward normal, in whole position steps; mass shifted past the
    /// window's ends stays in the end positions.
    void shift(Vec2 move);

    int taps() const { return taps_; }
    int best() const;  ///< argmax, lowest index on ties
    double bestPosterior() const;
    double posterior(int cls) const;  ///< exp of the normalised log posterior
    const std::vector<double>& logPosterior() const { return logPosterior_; }

    /// What the belief decides on: percepts, not classes. The percept is the most likely
    /// class's (best()); an edge class is a percept of its own, while the plane classes together
    /// are one (the tip rests on the surface: no orientation or position to tell), and so are the
    /// air classes. This is the belief in that percept: the class's posterior for an edge, its
    /// region's summed posterior for plane and air. Without regions every class is an edge.
    double perceptBelief() const;
    bool decided(double threshold) const { return perceptBelief() >= threshold; }

private:
    ClassSet classes_;
    std::vector<double> logPosterior_;
    std::vector<double> scratch_;
    int taps_ = 0;
};

}  // namespace activetouch
