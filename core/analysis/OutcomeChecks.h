#pragma once
// What every seed's outcome read from a shard file must satisfy before it counts in a rate: a
// file from another machine is proven by its run.json's digest, and then each value is held to
// what a run can produce (docs/limits.md, "Shards"). A value that breaks one is refused by file,
// place and what is wrong, so that no rate ever reads "132 / 32".
#include <string>

#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"

namespace activetouch {

/// The most robot time one seed's run may report: about 32 years, beyond any plan a run accepts.
inline constexpr double kMaxSeedRobotTime_s = 1e9;

/// Refuses (InputError(path, place + "/key", ...)) an outcome with a count below 0 or a part above
/// its whole (lost or completed above the trials, a rate's count above its total, more namings
/// than completed trials), a time or error that is not finite and non-negative or is beyond
/// kMaxSeedRobotTime_s, or a valid range that runs backwards.
void checkSeedOutcome(const SeedOutcome& o, const std::string& path, const std::string& place);

/// The same for one seed's record of a comparison: robot times finite, non-negative, bounded.
void checkSeedPairRecord(const SeedPairRecord& r, const std::string& path,
                         const std::string& place);

}  // namespace activetouch
