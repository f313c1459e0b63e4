#include "core/analysis/ComparisonShards.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <tuple>

#include "core/common/InputError.h"
#include "core/io/JsonFields.h"
#include "core/analysis/OutcomeChecks.h"
#include "core/run/OutputFiles.h"
#include "core/run/RunFolder.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

constexpr const char* kComparisonShardFile = "compare_seeds.json";

Json trialJson(const SeedPairRecord::Trial& t) {
    const PairedTrial& p = t.pair;
    return {{"mode", modeName(p.mode)},
            {"label", p.label},
            {"trial", p.trial},
            {"outcome", {p.outcomeA, p.outcomeB}},
            {"named", {p.namedA, p.namedB}},
            {"completed", {t.completedA, t.completedB}},
            {"at_a_corner", {t.atCornerA, t.atCornerB}},
            {"recognition_applies", t.recognitionApplies},
            {"named_rightly", {t.namedRightA, t.namedRightB}}};
}

Json recordJson(const SeedPairRecord& r) {
    Json trials = Json::array();
    for (const auto& t : r.trials) trials.push_back(trialJson(t));
    return {{"seed", r.seed},
            {"failed_runs", r.failedRuns},
            {"robot_time_s", {r.robotTimeA_s, r.robotTimeB_s}},
            {"unpaired_trials", r.unpairedTrials},
            {"trials", trials},
            {"paper_result_applies", r.paperResultApplies},
            {"paper_result", {r.paperResultA, r.paperResultB}}};
}

const Json& need(const JsonFields& f, const char* key) {
    if (!f.has(key)) f.fail(key, "missing; the file is damaged");
    return f.raw(key);
}

bool boolAt(const JsonFields& f, const char* key) {
    const Json& v = need(f, key);
    if (!v.is_boolean()) f.fail(key, "expected true or false; the file is damaged");
    return v.get<bool>();
}

/// The pair of values at `key` of `f`, each of type T.
template <typename T>
std::pair<T, T> pairAt(const JsonFields& f, const char* key) {
    const Json& v = need(f, key);
    if (!v.is_array() || v.size() != 2) f.fail(key, "expected [a, b]; the file is damaged");
    try {
        return {v[0].get<T>(), v[1].get<T>()};
    } catch (const std::exception&) {
        f.fail(key, "expected [a, b] of the right kind; the file is damaged");
    }
    return {};
}

SeedPairRecord recordFromJson(const Json& j, const std::string& path, const std::string& place) {
    if (!j.is_object()) throw InputError(path, place, "expected a seed's record; the file is damaged");
    JsonFields f(j, path, place);
    f.rejectUnknownKeys({"seed", "failed_runs", "robot_time_s", "unpaired_trials", "trials",
                         "paper_result_applies", "paper_result"});
    SeedPairRecord r;
    const Json& seed = need(f, "seed");
    if (!seed.is_number_unsigned()) f.fail("seed", "expected a seed; the file is damaged");
    r.seed = seed.get<std::uint64_t>();
    const Json& failed = need(f, "failed_runs");
    if (!failed.is_array()) f.fail("failed_runs", "expected a list of texts; the file is damaged");
    for (const Json& line : failed) {
        if (!line.is_string()) f.fail("failed_runs", "expected a list of texts; the file is damaged");
        r.failedRuns.push_back(line.get<std::string>());
    }
    std::tie(r.robotTimeA_s, r.robotTimeB_s) = pairAt<double>(f, "robot_time_s");
    r.unpairedTrials = f.integer("unpaired_trials", 0, 1000000);
    r.paperResultApplies = boolAt(f, "paper_result_applies");
    std::tie(r.paperResultA, r.paperResultB) = pairAt<bool>(f, "paper_result");
    const Json& trials = need(f, "trials");
    if (!trials.is_array()) f.fail("trials", "expected the paired trials; the file is damaged");
    for (std::size_t i = 0; i < trials.size(); ++i) {
        const std::string at = place + "/trials/" + std::to_string(i);
        if (!trials[i].is_object())
            throw InputError(path, at, "expected a paired trial; the file is damaged");
        JsonFields t(trials[i], path, at);
        t.rejectUnknownKeys({"mode", "label", "trial", "outcome", "named", "completed",
                             "at_a_corner", "recognition_applies", "named_rightly"});
        SeedPairRecord::Trial out;
        const std::string mode = t.text("mode");
        if (mode != "active" && mode != "passive")
            t.fail("mode", "expected active or passive; the file is damaged");
        out.pair.seed = r.seed;
        out.pair.mode = mode == "active" ? FollowingMode::Active : FollowingMode::Passive;
        out.pair.label = t.text("label");
        out.pair.trial = t.integer("trial", 1, 1000000);
        std::tie(out.pair.outcomeA, out.pair.outcomeB) =
            pairAt<std::string>(t, "outcome");
        std::tie(out.pair.namedA, out.pair.namedB) = pairAt<std::string>(t, "named");
        std::tie(out.completedA, out.completedB) = pairAt<bool>(t, "completed");
        std::tie(out.atCornerA, out.atCornerB) = pairAt<bool>(t, "at_a_corner");
        out.recognitionApplies = boolAt(t, "recognition_applies");
        std::tie(out.namedRightA, out.namedRightB) = pairAt<bool>(t, "named_rightly");
        r.trials.push_back(std::move(out));
    }
    checkSeedPairRecord(r, path, place);
    return r;
}

}  // namespace

bool holdsComparisonShard(const std::string& dir) {
    std::error_code ec;
    return fs::is_regular_file(fs::path(dir) / kComparisonShardFile, ec);
}

void writeComparisonShardFile(const std::string& dir, const ComparisonShardFile& f) {
    Json records = Json::array();
    for (const SeedPairRecord& r : f.records) records.push_back(recordJson(r));
    writeJsonAtomically((fs::path(dir) / kComparisonShardFile).string(),
                        {{"a", f.nameA},
                         {"b", f.nameB},
                         {"fingerprint", f.fingerprint},
                         {"range", {f.first, f.last}},
                         {"shard", {f.shard.index, f.shard.count}},
                         {"seeds", records}});
}

ComparisonShardFile readComparisonShardFile(const std::string& dir) {
    const std::string path = (fs::path(dir) / kComparisonShardFile).string();
    if (!holdsComparisonShard(dir))
        throw InputError(dir, "",
                         "holds no compare_seeds.json: it is not a folder a compare run (with or "
                         "without --shard) wrote, or that run did not finish");
    const Json j = readJsonFile(path);
    JsonFields f(j, path, "");
    f.rejectUnknownKeys({"a", "b", "fingerprint", "range", "shard", "seeds"});
    ComparisonShardFile s;
    s.nameA = f.text("a");
    s.nameB = f.text("b");
    s.fingerprint = f.text("fingerprint");
    readShardPlace(f, &s.first, &s.last, &s.shard);
    const Json& seeds = need(f, "seeds");
    if (!seeds.is_array()) f.fail("seeds", "expected each seed's record; the file is damaged");
    for (std::size_t i = 0; i < seeds.size(); ++i)
        s.records.push_back(recordFromJson(seeds[i], path, "/seeds/" + std::to_string(i)));
    return s;
}

ComparisonShardFile mergeComparisonShards(const std::vector<std::string>& dirs) {
    if (dirs.empty()) throw InputError("merge", "", "give the folders of the shards to merge");
    std::vector<ComparisonShardFile> parts;
    std::vector<ShardPart> cover;
    for (const std::string& d : dirs) {
        checkProvenRun(d, kComparisonShardFile);
        parts.push_back(readComparisonShardFile(d));
        const ComparisonShardFile& p = parts.back();
        ShardPart c{d, "'" + p.nameA + "' against '" + p.nameB + "'", p.fingerprint, p.first,
                    p.last, p.shard, {}};
        for (const SeedPairRecord& r : p.records) c.seeds.push_back(r.seed);
        cover.push_back(std::move(c));
    }
    checkShardsCover(cover, "compare");
    ComparisonShardFile merged = parts.front();
    merged.shard = {1, 1};
    merged.records.clear();
    for (const ComparisonShardFile& p : parts)
        merged.records.insert(merged.records.end(), p.records.begin(), p.records.end());
    std::sort(merged.records.begin(), merged.records.end(),
              [](const SeedPairRecord& a, const SeedPairRecord& b) { return a.seed < b.seed; });
    return merged;
}

PairedComparison writeMergedComparison(const ComparisonShardFile& merged,
                                       const std::string& outDir) {
    PairedComparison c;
    c.nameA = merged.nameA;
    c.nameB = merged.nameB;
    std::optional<OutputFile> table, soFar;
    startComparisonTables(table, soFar, outDir);
    for (const SeedPairRecord& r : merged.records) {
        std::vector<PairedTrial> pairs;
        addSeedRecord(c, r, &pairs);
        appendComparedSeed(*table, *soFar, c, pairs);
    }
    table->close();
    soFar->close();
    writeJsonAtomically((fs::path(outDir) / "compare.json").string(), pairedComparisonJson(c));
    writeComparisonShardFile(outDir, merged);
    return c;
}

}  // namespace activetouch
