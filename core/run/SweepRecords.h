#pragma once
// One run's sweeps as its summary gives them and as a seed keeps them (docs/accuracy-vs-time.md):
// the robustness rows and the bandit as JSON and text, the whole sweep results as JSON and back,
// and the names of the sweep's settings.
#include <string>
#include <vector>

#include "core/io/JsonFields.h"
#include "core/run/SweepResults.h"

namespace activetouch {

/// "single tap", or "threshold 0.9".
std::string thresholdName(double threshold);
/// "active 2/1 mm, single tap", "passive 2 mm, threshold 0.9".
std::string settingName(FollowingMode mode, double follow, double reposition, double threshold);
/// The name of a row of the following sweep, per run or over seeds.
template <typename Row>
std::string settingName(const Row& r) {
    return settingName(r.mode, r.followStep_mm, r.repositionStep_mm, r.beliefThreshold);
}

/// `first` followed by `rest`: the single tap then the thresholds, the base then the faults.
template <typename Row>
std::vector<Row> firstThen(const Row& first, const std::vector<Row>& rest) {
    std::vector<Row> all{first};
    all.insert(all.end(), rest.begin(), rest.end());
    return all;
}

/// One run's robustness rows as JSON (summary.json's sweeps.robustness) and as lines of text.
Json robustnessJson(const SweepResults& sweeps);
std::vector<std::string> describeRobustness(const SweepResults& sweeps);

/// One run's bandit as JSON (summary.json's sweeps.bandit) and as a line of text.
Json banditJson(const BanditResult& bandit, const std::vector<FollowingSweepRow>& following);
std::string describeBandit(const BanditResult& bandit,
                           const std::vector<FollowingSweepRow>& following);

/// What a seed keeps of its run's sweeps, and back: enough to aggregate over seeds (the per-run
/// intervals over classes are not kept).
Json seedSweepsJson(const SweepResults& sweeps);
SweepResults seedSweepsFromJson(const Json& j);

}  // namespace activetouch
