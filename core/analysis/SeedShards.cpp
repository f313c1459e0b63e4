#include "core/analysis/SeedShards.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "core/analysis/OutcomeChecks.h"
#include "core/analysis/SeedJournal.h"
#include "core/analysis/SweepRates.h"
#include "core/common/InputError.h"
#include "core/io/JsonFields.h"
#include "core/run/OutputFiles.h"
#include "core/run/RunFolder.h"

namespace activetouch {
namespace fs = std::filesystem;

namespace {

constexpr const char* kShardFile = "seed_outcomes.json";

Json rateJsonOf(const Rate& r) {
    return {r.count, r.total};
}

Rate rateOf(const Json& j) {
    if (!j.is_array() || j.size() != 2 || !j[0].is_number_integer() || !j[1].is_number_integer())
        throw std::invalid_argument("a rate is [count, total]");
    return {j[0].get<int>(), j[1].get<int>()};
}

Json byLabelJson(const RatesByLabel& rates) {
    Json list = Json::array();
    for (const auto& [label, rate] : rates) list.push_back({label, rateJsonOf(rate)});
    return list;
}

RatesByLabel byLabelOf(const Json& j) {
    RatesByLabel rates;
    for (const Json& entry : j)
        rates.emplace_back(entry.at(0).get<std::string>(), rateOf(entry.at(1)));
    return rates;
}

Json tracingJson(const Tracing& t) {
    return {{"trials", t.trials},
            {"coverage_sum", t.coverageSum},
            {"mean_distance_sum_mm", t.meanDistanceSum_mm}};
}

Tracing tracingOf(const Json& j) {
    return {j.at("trials").get<int>(), j.at("coverage_sum").get<double>(),
            j.at("mean_distance_sum_mm").get<double>()};
}

Json cornersJson(const CornerTally& c) {
    return {{"ended_convex", c.endedConvex},
            {"ended_concave", c.endedConcave},
            {"ended_away", c.endedAway},
            {"rounded_convex", c.rounded.convex},
            {"rounded_concave", c.rounded.concave}};
}

CornerTally cornersOf(const Json& j) {
    CornerTally c;
    c.endedConvex = j.at("ended_convex").get<int>();
    c.endedConcave = j.at("ended_concave").get<int>();
    c.endedAway = j.at("ended_away").get<int>();
    c.rounded.convex = j.at("rounded_convex").get<int>();
    c.rounded.concave = j.at("rounded_concave").get<int>();
    return c;
}

// FNV-1a, 64 bits: a fingerprint, not a defence against anyone forging one.
std::string fnv1a(const std::string& text) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string seedList(const std::vector<std::uint64_t>& seeds) {
    // 3, 5-9, 12: runs of consecutive seeds shortened.
    std::string out;
    for (std::size_t i = 0; i < seeds.size();) {
        std::size_t j = i;
        while (j + 1 < seeds.size() && seeds[j + 1] == seeds[j] + 1) ++j;
        if (!out.empty()) out += ", ";
        out += std::to_string(seeds[i]);
        if (j > i) {
            out += '-';
            out += std::to_string(seeds[j]);
        }
        i = j + 1;
    }
    return out;
}

std::string shardName(const Shard& s) {
    return std::to_string(s.index) + "/" + std::to_string(s.count);
}

// Each folder holds exactly the seeds of its own block, and claims its K/N alone.
void checkShardBlocks(const std::vector<ShardPart>& parts) {
    std::map<int, std::size_t> claimedBy;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const ShardPart& p = parts[i];
        const auto block = shardSeeds(p.first, p.last, p.shard);
        const std::string blockText =
            block ? "seeds " + std::to_string(block->first) + "-" + std::to_string(block->second)
                  : std::string("no seed");
        for (const std::uint64_t seed : p.seeds)
            if (!block || seed < block->first || seed > block->second)
                throw InputError(p.dir, "",
                                 "holds seed " + std::to_string(seed) + ", but as shard " +
                                     shardName(p.shard) + " of " + std::to_string(p.first) + "-" +
                                     std::to_string(p.last) + " its block is " + blockText +
                                     "; the folder is damaged: run that shard again");
        const std::uint64_t want = block ? block->second - block->first + 1 : 0;
        if (p.seeds.size() != want)
            throw InputError(p.dir, "",
                             "holds " + std::to_string(p.seeds.size()) +
                                 " seeds' outcomes, but its block as shard " + shardName(p.shard) +
                                 " is " + blockText + " (" + std::to_string(want) +
                                 "); the folder is damaged or was cut short: run that shard again");
        const auto [at, fresh] = claimedBy.emplace(p.shard.index, i);
        if (!fresh && parts[at->second].dir != p.dir)
            throw InputError("merge", "",
                             parts[at->second].dir + " and " + p.dir + " both claim shard " +
                                 shardName(p.shard) + "; give each shard's folder once");
    }
}

}  // namespace

std::optional<Shard> parseShard(const std::string& text, std::string* error) {
    int k = 0, n = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d/%d%c", &k, &n, &tail) != 2 || n < 1 || n > 100000 || k < 1 ||
        k > n) {
        if (error)
            *error = "--shard '" + text +
                     "' is not a shard; give K/N with 1 <= K <= N, e.g. --shard 2/3 for the "
                     "second of three";
        return std::nullopt;
    }
    return Shard{k, n};
}

std::optional<std::pair<std::uint64_t, std::uint64_t>> shardSeeds(std::uint64_t first,
                                                                  std::uint64_t last,
                                                                  const Shard& shard) {
    const std::uint64_t count = last - first + 1;
    const auto edge = [&](std::uint64_t k) {
        // first + floor(k * count / N), without overflow for any range of seeds.
        return first + (count / shard.count) * k + (count % shard.count) * k / shard.count;
    };
    const std::uint64_t begin = edge(shard.index - 1), end = edge(shard.index);
    if (begin >= end) return std::nullopt;
    return std::pair(begin, end - 1);
}

std::string experimentFingerprint(const std::string& path, const ExperimentSpec& spec) {
    Json j = readExperimentFile(path);
    j["scene"] = sceneToJson(spec.scene);  // the scene as it runs, wherever its file lies
    j.erase("description");
    return fnv1a(j.dump());
}

Json seedOutcomeJson(const SeedOutcome& o) {
    Json namings = Json::array();
    for (const PathNaming& n : o.namings)
        namings.push_back(
            {n.label, n.trial, n.raw, n.smoothed, n.anyPose, n.turnError_deg, n.placeError_mm});
    return {{"seed", o.seed},
            {"passive_trials", o.passiveTrials},
            {"passive_lost", o.passiveLost},
            {"active_trials", o.activeTrials},
            {"active_completed", o.activeCompleted},
            {"recognition", o.recognition},
            {"completed_taps", o.completedTaps},
            {"completed_robot_time_s", o.completedRobotTime_s},
            {"run_robot_time_s", o.runRobotTime_s},
            {"angle_error_deg", o.angleError_deg},
            {"position_error_mm", o.positionError_mm},
            {"valid_range", {o.validRange.first, o.validRange.last, o.validRange.score}},
            {"run_failure", o.runFailure},
            {"trials_not_run", o.trialsNotRun},
            {"active_failures", o.failures},
            {"passive_shortfalls", o.passiveShortfalls},
            {"namings", namings},
            {"active_by_label", byLabelJson(o.activeByLabel)},
            {"passive_by_label", byLabelJson(o.passiveByLabel)},
            {"active_tracing", tracingJson(o.activeTracing)},
            {"passive_tracing", tracingJson(o.passiveTracing)},
            {"active_corners", cornersJson(o.activeCorners)},
            {"passive_corners", cornersJson(o.passiveCorners)},
            {"sweeps", o.sweeps.empty() ? Json() : seedSweepsJson(o.sweeps)}};
}

SeedOutcome seedOutcomeFromJson(const Json& j, const std::string& source,
                                const std::string& place) {
    SeedOutcome o;
    try {
        o.seed = j.at("seed").get<std::uint64_t>();
        o.passiveTrials = j.at("passive_trials").get<int>();
        o.passiveLost = j.at("passive_lost").get<int>();
        o.activeTrials = j.at("active_trials").get<int>();
        o.activeCompleted = j.at("active_completed").get<int>();
        o.recognition = j.at("recognition").get<bool>();
        o.completedTaps = j.at("completed_taps").get<int>();
        o.completedRobotTime_s = j.at("completed_robot_time_s").get<double>();
        o.runRobotTime_s = j.at("run_robot_time_s").get<double>();
        o.angleError_deg = j.at("angle_error_deg").get<double>();
        o.positionError_mm = j.at("position_error_mm").get<double>();
        const Json& range = j.at("valid_range");
        o.validRange = {range.at(0).get<int>(), range.at(1).get<int>(), range.at(2).get<double>()};
        o.runFailure = j.at("run_failure").get<std::string>();
        o.trialsNotRun = j.at("trials_not_run").get<int>();
        o.failures = j.at("active_failures").get<std::vector<std::string>>();
        o.passiveShortfalls = j.at("passive_shortfalls").get<std::vector<std::string>>();
        for (const Json& n : j.at("namings"))
            o.namings.push_back({n.at(0).get<std::string>(), n.at(1).get<int>(),
                                 n.at(2).get<std::string>(), n.at(3).get<std::string>(),
                                 n.at(4).get<std::string>(), n.at(5).get<double>(),
                                 n.at(6).get<double>()});
        o.activeByLabel = byLabelOf(j.at("active_by_label"));
        o.passiveByLabel = byLabelOf(j.at("passive_by_label"));
        o.activeTracing = tracingOf(j.at("active_tracing"));
        o.passiveTracing = tracingOf(j.at("passive_tracing"));
        o.activeCorners = cornersOf(j.at("active_corners"));
        o.passiveCorners = cornersOf(j.at("passive_corners"));
        if (const auto sweeps = j.find("sweeps"); sweeps != j.end() && !sweeps->is_null())
            o.sweeps = seedSweepsFromJson(*sweeps);
    } catch (const std::exception& e) {
        throw InputError(source, place,
                         std::string("a seed's outcome cannot be read (") + e.what() +
                             "); the file is damaged: run that shard again");
    }
    checkSeedOutcome(o, source, place);
    return o;
}

void writeSeedShardFile(const std::string& dir, const SeedShardFile& f) {
    Json outcomes = Json::array();
    for (const SeedOutcome& o : f.outcomes) outcomes.push_back(seedOutcomeJson(o));
    writeJsonAtomically((fs::path(dir) / kShardFile).string(),
                        {{"experiment", f.experiment},
                         {"fingerprint", f.fingerprint},
                         {"range", {f.first, f.last}},
                         {"shard", {f.shard.index, f.shard.count}},
                         {"outcomes", outcomes}});
}

void readShardPlace(const JsonFields& f, std::uint64_t* first, std::uint64_t* last, Shard* shard) {
    static const Json kMissing;
    const Json& range = f.has("range") ? f.raw("range") : kMissing;
    const Json& part = f.has("shard") ? f.raw("shard") : kMissing;
    if (!range.is_array() || range.size() != 2 || !range[0].is_number_unsigned() ||
        !range[1].is_number_unsigned() ||
        range[0].get<std::uint64_t>() > range[1].get<std::uint64_t>())
        f.fail("range", "expected [first, last] seeds; the file is damaged");
    if (!part.is_array() || part.size() != 2 || !part[0].is_number_integer() ||
        !part[1].is_number_integer() || part[0].get<int>() < 1 ||
        part[0].get<int>() > part[1].get<int>())
        f.fail("shard", "expected [K, N]; the file is damaged");
    *first = range[0].get<std::uint64_t>();
    *last = range[1].get<std::uint64_t>();
    *shard = {part[0].get<int>(), part[1].get<int>()};
}

SeedShardFile readSeedShardFile(const std::string& dir) {
    const std::string path = (fs::path(dir) / kShardFile).string();
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(dir, "",
                         "holds no seed_outcomes.json: it is not a folder a seeds run (with or "
                         "without --shard) wrote, or that run did not finish");
    const Json j = readJsonFile(path);
    JsonFields f(j, path, "");
    f.rejectUnknownKeys({"experiment", "fingerprint", "range", "shard", "outcomes"});
    SeedShardFile s;
    s.experiment = f.text("experiment");
    s.fingerprint = f.text("fingerprint");
    readShardPlace(f, &s.first, &s.last, &s.shard);
    const Json& outcomes = f.raw("outcomes");
    if (!outcomes.is_array()) f.fail("outcomes", "expected each seed's outcome");
    for (std::size_t i = 0; i < outcomes.size(); ++i)
        s.outcomes.push_back(
            seedOutcomeFromJson(outcomes[i], path, "/outcomes/" + std::to_string(i)));
    return s;
}

void checkShardsCover(const std::vector<ShardPart>& parts, const std::string& command) {
    if (parts.empty()) throw InputError("merge", "", "give the folders of the shards to merge");
    const ShardPart& first = parts.front();
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const ShardPart& p = parts[i];
        if (p.fingerprint != first.fingerprint || p.ran != first.ran)
            throw InputError(p.dir, "",
                             "ran " + p.ran + " with other settings than " + first.dir + " (" +
                                 first.ran + "); merge only shards of one " + command + " run");
        if (p.first != first.first || p.last != first.last || p.shard.count != first.shard.count)
            throw InputError(p.dir, "",
                             "is shard " + std::to_string(p.shard.index) + "/" +
                                 std::to_string(p.shard.count) + " of seeds " +
                                 std::to_string(p.first) + "-" + std::to_string(p.last) + ", but " +
                                 first.dir + " is shard " + std::to_string(first.shard.index) +
                                 "/" + std::to_string(first.shard.count) + " of seeds " +
                                 std::to_string(first.first) + "-" + std::to_string(first.last) +
                                 "; merge shards of one range, split one way");
    }
    checkShardBlocks(parts);
    // Every seed once: which folder holds it.
    std::map<std::uint64_t, std::size_t> holder;
    std::map<std::pair<std::size_t, std::size_t>, std::vector<std::uint64_t>> overlaps;
    for (std::size_t i = 0; i < parts.size(); ++i)
        for (const std::uint64_t seed : parts[i].seeds) {
            if (seed < first.first || seed > first.last)
                throw InputError(parts[i].dir, "",
                                 "holds seed " + std::to_string(seed) + ", outside its range " +
                                     std::to_string(first.first) + "-" +
                                     std::to_string(first.last) + "; the folder is damaged");
            const auto [at, fresh] = holder.emplace(seed, i);
            if (!fresh) overlaps[{at->second, i}].push_back(seed);
        }
    if (!overlaps.empty()) {
        std::string text;
        for (const auto& [pair, seeds] : overlaps)
            text += (text.empty() ? "" : "; ") + std::string("seeds ") + seedList(seeds) +
                    " are in both " + parts[pair.first].dir + " and " + parts[pair.second].dir;
        throw InputError("merge", "", "the shards overlap: " + text + "; merge each shard once");
    }
    std::vector<std::uint64_t> missing;
    for (std::uint64_t s = first.first; s <= first.last && missing.size() < 100000; ++s) {
        if (!holder.count(s)) missing.push_back(s);
        if (s == first.last) break;
    }
    if (missing.empty()) return;
    std::vector<int> shards;
    for (int k = 1; k <= first.shard.count; ++k)
        if (const auto block = shardSeeds(first.first, first.last, {k, first.shard.count}))
            for (const std::uint64_t s : missing)
                if (s >= block->first && s <= block->second) {
                    shards.push_back(k);
                    break;
                }
    std::string named;
    for (const int k : shards)
        named += (named.empty() ? "" : ", ") + std::to_string(k) + "/" +
                 std::to_string(first.shard.count);
    throw ShardsToRerun("seeds " + seedList(missing) + " of " + std::to_string(first.first) + "-" +
                            std::to_string(first.last) + " are in no shard given: shards " + named +
                            "; run them (" + command + " --shard K/" +
                            std::to_string(first.shard.count) + ") and give their folders too",
                        shards);
}

namespace {

/// Refuses, naming every one, shard folders whose run was cut short (their journal is still
/// there): rerunning each with the command that started it finishes it.
void refuseCutShort(const std::vector<std::string>& dirs) {
    std::string named;
    std::vector<int> shards;
    for (const std::string& d : dirs)
        if (const auto c = cutShortShard(d)) {
            shards.push_back(c->shard.index);
            named += (named.empty() ? "" : "; ") + d + " (shard " + std::to_string(c->shard.index) +
                     "/" + std::to_string(c->shard.count) + ", " + std::to_string(c->seedsDone) +
                     " seeds done)";
        }
    if (!shards.empty())
        throw ShardsToRerun("these shards were cut short: " + named +
                                "; rerun each with the command that started it, which resumes "
                                "it where it stopped",
                            shards);
}

}  // namespace

SeedShardFile mergeSeedShards(const std::vector<std::string>& dirs) {
    if (dirs.empty()) throw InputError("merge", "", "give the folders of the shards to merge");
    std::vector<SeedShardFile> parts;
    std::vector<ShardPart> cover;
    refuseCutShort(dirs);
    for (const std::string& d : dirs) {
        checkProvenRun(d, kShardFile);
        parts.push_back(readSeedShardFile(d));
        const SeedShardFile& p = parts.back();
        ShardPart c{d, "'" + p.experiment + "'", p.fingerprint, p.first, p.last, p.shard, {}};
        for (const SeedOutcome& o : p.outcomes) c.seeds.push_back(o.seed);
        cover.push_back(std::move(c));
    }
    checkShardsCover(cover, "seeds");
    SeedShardFile merged = parts.front();
    merged.shard = {1, 1};
    merged.outcomes.clear();
    for (const SeedShardFile& p : parts)
        merged.outcomes.insert(merged.outcomes.end(), p.outcomes.begin(), p.outcomes.end());
    std::sort(merged.outcomes.begin(), merged.outcomes.end(),
              [](const SeedOutcome& a, const SeedOutcome& b) { return a.seed < b.seed; });
    return merged;
}

SeedRates writeMergedSeeds(const SeedShardFile& merged, const std::string& outDir) {
    SeedRates rates;
    std::optional<OutputFile> table;
    startRatesTable(table, outDir);
    for (const SeedOutcome& o : merged.outcomes) {
        rates.seeds.push_back(o);
        appendRatesRow(*table, o);
    }
    table->close();
    writeSeedRatesFiles(rates, outDir);
    writeSeedShardFile(outDir, merged);
    return rates;
}

}  // namespace activetouch
