#pragma once
// Sweeps over seeds split across machines (docs/command-line.md, "Across machines"): `seeds
// --shard K/N` runs the K-th of N contiguous blocks of the seed range and writes a partial folder;
// `merge` reads the partial folders and writes exactly what one run over every seed writes. Every
// seeds folder keeps each seed's whole outcome in seed_outcomes.json, so that nothing is
// recomputed or approximated on merging.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/SeedRates.h"
#include "core/io/JsonFields.h"

namespace activetouch {

/// Shard K of N (1 <= K <= N).
struct Shard {
    int index = 1, count = 1;
};

/// "K/N" read as a shard; an error names the option and what it needs.
std::optional<Shard> parseShard(const std::string& text, std::string* error);

/// The seeds of `shard` of first..last: the range cut into N contiguous blocks as even as can be,
/// in order. Empty (nothing) for a shard with no seed (more shards than seeds).
std::optional<std::pair<std::uint64_t, std::uint64_t>> shardSeeds(std::uint64_t first,
                                                                  std::uint64_t last,
                                                                  const Shard& shard);

/// What a seeds folder holds beside its rates: the experiment (its name and a fingerprint of its
/// resolved settings), the whole range and the shard, and every seed's outcome.
struct SeedShardFile {
    std::string experiment, fingerprint;
    std::uint64_t first = 0, last = 0;
    Shard shard;
    std::vector<SeedOutcome> outcomes;
};

/// A fingerprint of everything the experiment at `path` runs with: shards of different settings
/// are never merged. Paths do not enter it, so machines with other checkouts agree.
std::string experimentFingerprint(const std::string& path, const ExperimentSpec& spec);

Json seedOutcomeJson(const SeedOutcome& o);
SeedOutcome seedOutcomeFromJson(const Json& j, const std::string& source, const std::string& place);

/// Reads a shard file's "range" ([first, last]) and "shard" ([K, N]); fails through `f`, naming
/// the key, if either is missing or damaged.
void readShardPlace(const JsonFields& f, std::uint64_t* first, std::uint64_t* last, Shard* shard);

/// Writes <dir>/seed_outcomes.json atomically.
void writeSeedShardFile(const std::string& dir, const SeedShardFile& file);
/// Reads <dir>/seed_outcomes.json; InputError naming the folder if it is no seeds folder.
SeedShardFile readSeedShardFile(const std::string& dir);

/// What a shard folder says of itself, to check that a set of them covers one range once.
struct ShardPart {
    std::string dir;
    std::string ran;  ///< what it ran, for messages: "'paper'", "'paper' against 'kernel'"
    std::string fingerprint;
    std::uint64_t first = 0, last = 0;  ///< the whole range
    Shard shard;
    std::vector<std::uint64_t> seeds;  ///< the seeds it holds
};

/// A merge refused because shards are missing or were cut short: which shards (K of N) to run
/// again, with the command that started them (a seeds shard cut short resumes where it stopped).
class ShardsToRerun : public InputError {
public:
    ShardsToRerun(std::string problem, std::vector<int> shards)
        : InputError("merge", "", std::move(problem)), shards_(std::move(shards)) {}
    const std::vector<int>& shards() const { return shards_; }

private:
    std::vector<int> shards_;
};

/// Refuses (InputError naming the seeds and the folders) shards that ran other settings, another
/// range or split, overlap, or leave seeds out. `command`: "seeds" or "compare", for the advice.
void checkShardsCover(const std::vector<ShardPart>& parts, const std::string& command);

/// The shards in `dirs` merged: checks they ran one experiment over one range in as many shards,
/// and refuses (InputError naming the seeds and the folders) shards that overlap or leave seeds
/// out. The outcomes come back in seed order.
SeedShardFile mergeSeedShards(const std::vector<std::string>& dirs);

/// Writes what a seeds run over `merged`'s range writes in `outDir`: rates.csv, rates.json and
/// seed_outcomes.json (figures are drawn by the caller). Returns the rates.
SeedRates writeMergedSeeds(const SeedShardFile& merged, const std::string& outDir);

}  // namespace activetouch
