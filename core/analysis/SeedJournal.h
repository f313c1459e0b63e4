#pragma once
// A seeds run's journal: each seed's whole outcome appended as it finishes, so that a run cut
// short (killed, pre-empted, stopped) resumes where it stopped instead of starting over
// (docs/command-line.md, "Across machines"). <dir>/seed_outcomes.journal holds one JSON object a
// line: first what the run is (experiment, fingerprint, range, shard), then one outcome a seed,
// in seed order. It is removed once the run's block is whole.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/SeedShards.h"

namespace activetouch {

class OutputFile;

inline constexpr const char* kSeedJournal = "seed_outcomes.journal";

/// What a cut-short run left: the outcomes of the first seeds of its block, in order.
struct JournalResume {
    std::vector<SeedOutcome> outcomes;
    std::uint64_t blockFirst = 0, blockLast = 0;  ///< the run's block of seeds
};

/// The journal in `dir`, if there is one, held to `run` (its experiment, fingerprint, range and
/// shard; `run.outcomes` unused) and to the block `first`..`last`. A last line cut short (the run
/// killed while writing it) is left out. Throws InputError naming the journal and what to do
/// where it belongs to another run, or a line other than the last is damaged, or its seeds are
/// not the block's first ones in order.
std::optional<JournalResume> readSeedJournal(const std::string& dir, const SeedShardFile& run,
                                             std::uint64_t first, std::uint64_t last);

/// What a shard folder whose journal is still there says of itself: a run cut short.
struct CutShortShard {
    Shard shard;
    std::uint64_t first = 0, last = 0;  ///< the whole range
    std::size_t seedsDone = 0;          ///< whole outcome lines after the header
};

/// The journal of `dir` read for its header and its count of outcomes (nothing if it has none);
/// InputError where its first line is damaged.
std::optional<CutShortShard> cutShortShard(const std::string& dir);

/// Appends outcomes to a journal, each line flushed as it is written.
class SeedJournal {
public:
    /// Starts <dir>/seed_outcomes.journal afresh with `run`'s header and the `done` outcomes.
    SeedJournal(const std::string& dir, const SeedShardFile& run,
                const std::vector<SeedOutcome>& done);
    ~SeedJournal();
    SeedJournal(const SeedJournal&) = delete;
    SeedJournal& operator=(const SeedJournal&) = delete;
    void append(const SeedOutcome& o);
    /// Closes and removes the journal: the run's block is whole.
    void finish();

private:
    std::unique_ptr<OutputFile> file_;
};

}  // namespace activetouch
