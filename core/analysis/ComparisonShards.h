#pragma once
// Comparisons split across machines (docs/command-line.md, "Across machines"): `compare --shard
// K/N` runs the K-th of N contiguous blocks of the seed range; every compare folder keeps each
// seed's record (SeedPairRecord) in compare_seeds.json, so that `merge` writes exactly what one
// comparison over every seed writes: compare.csv, compare_so_far.csv and compare.json.
#include <cstdint>
#include <string>
#include <vector>

#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedShards.h"

namespace activetouch {

struct ComparisonShardFile {
    std::string nameA, nameB;
    std::string fingerprint;  ///< both experiments' fingerprints, "a+b"
    std::uint64_t first = 0, last = 0;
    Shard shard;
    std::vector<SeedPairRecord> records;  ///< in seed order
};

/// Whether `dir` holds a comparison's compare_seeds.json (else it may be a seeds folder).
bool holdsComparisonShard(const std::string& dir);

/// Writes <dir>/compare_seeds.json atomically.
void writeComparisonShardFile(const std::string& dir, const ComparisonShardFile& file);
/// Reads <dir>/compare_seeds.json; InputError naming the file and the place if it is damaged.
ComparisonShardFile readComparisonShardFile(const std::string& dir);

/// The shards in `dirs` merged, refused as seeds shards are (checkShardsCover).
ComparisonShardFile mergeComparisonShards(const std::vector<std::string>& dirs);

/// Writes what a comparison over `merged`'s range writes in `outDir` (figures are drawn by the
/// caller) and returns the comparison.
PairedComparison writeMergedComparison(const ComparisonShardFile& merged,
                                       const std::string& outDir);

}  // namespace activetouch
