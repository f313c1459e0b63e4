// The files merge reads from shard folders that other machines wrote: a seeds shard's
// seed_outcomes.json and a comparison shard's compare_seeds.json, the input given as each.
#include <filesystem>

#include "core/common/InputError.h"
#include "core/analysis/ComparisonShards.h"
#include "core/analysis/SeedShards.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string dir = fuzz::folder() + "/shard";
    std::filesystem::create_directories(dir);
    for (const char* name : {"seed_outcomes.json", "compare_seeds.json"})
        fuzz::writeInput("shard/" + std::string(name), data, size);
    try {
        readSeedShardFile(dir);
    } catch (const InputError&) {
    }
    try {
        readComparisonShardFile(dir);
    } catch (const InputError&) {
    }
    return 0;
}
