#include "core/run/RunFolder.h"

#include <chrono>
#include <ctime>
#include <filesystem>
#include <random>

#include "core/common/InputError.h"
#include "core/experiment/Experiment.h"
#include "core/io/FileDigest.h"
#include "core/io/InputFile.h"
#include "core/io/JsonFields.h"
#include "core/run/OutputFiles.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {
namespace fs = std::filesystem;

namespace {

constexpr const char* kManifest = "run.json";

std::string newRunId() {
    std::random_device device;
    const auto now = std::chrono::system_clock::now().time_since_epoch().count();
    std::mt19937_64 bits(device() ^ static_cast<std::uint64_t>(now));
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(bits()));
    return buf;
}

std::string isoNow() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

Json manifestJson(const RunManifest& m) {
    Json j;
    j["run_id"] = m.runId;
    j["command"] = m.command;
    j["experiment"] = m.experiment;
    j["started"] = m.started;
    j["samples_per_tap"] = m.facts.samplesPerTap;
    j["taxels"] = m.facts.taxels;
    j["stage_travel_mm"] = {m.facts.stageTravel_mm.x, m.facts.stageTravel_mm.y};
    j["finished"] = m.finished;
    if (m.finished) {
        Json files = Json::object();
        for (const auto& [name, stamp] : m.files)
            files[name] = {{"bytes", stamp.bytes}, {"sha256", stamp.sha256}};
        j["files"] = files;
    }
    return j;
}

// Every run artefact under `dir`, relative, with its size and (with `digests`) its SHA-256.
std::map<std::string, FileStamp> artefactsIn(const std::string& dir, bool digests) {
    std::map<std::string, FileStamp> files;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path relative = it->path().lexically_relative(dir);
        if (!isRunArtefact(relative.begin()->string())) {
            if (it->is_directory()) it.disable_recursion_pending();
            continue;
        }
        if (!it->is_regular_file()) continue;
        const std::string name = relative.generic_string();
        if (name == kManifest) continue;
        FileStamp& stamp = files[name];
        stamp.bytes = it->file_size(ec);
        ec.clear();
        if (digests) stamp.sha256 = sha256OfFile(it->path().string());
    }
    return files;
}

bool isHexDigest(const std::string& text) {
    return text.size() == 64 && text.find_first_not_of("0123456789abcdef") == std::string::npos;
}

// A file's entry in run.json: {"bytes": N, "sha256": "..."}, or a bare size as run folders
// written before digests were kept record it (read with an empty digest: its size is checked).
FileStamp stampOf(Json::const_iterator entry, const std::string& file) {
    const Json& v = entry.value();
    if (v.is_number_unsigned()) return {v.get<std::uintmax_t>(), ""};
    const auto bytes = v.is_object() ? v.find("bytes") : v.end();
    const auto digest = v.is_object() ? v.find("sha256") : v.end();
    if (bytes == v.end() || !bytes->is_number_unsigned() || digest == v.end() ||
        !digest->is_string() || !isHexDigest(digest->get<std::string>()))
        throw InputError(file, "/files/" + entry.key(),
                         "expected the file's size in bytes and its SHA-256 ({\"bytes\": N, "
                         "\"sha256\": \"64 hex digits\"}); the manifest is damaged");
    return {bytes->get<std::uintmax_t>(), digest->get<std::string>()};
}

}  // namespace

bool isRunArtefact(const std::string& name) {
    static const char* const kNames[] = {"run.json",
                                         "summary.json",
                                         "rates.csv",
                                         "rates.json",
                                         "compare.csv",
                                         "compare_so_far.csv",
                                         "compare.json",
                                         "import.json",
                                         "data",
                                         "figures",
                                         "seed_outcomes.json",
                                         "compare_seeds.json",
                                         "seed_outcomes.journal"};
    for (const char* n : kNames)
        if (name == n) return true;
    const auto endsWith = [&](const char* tail) {
        const std::string t(tail);
        return name.size() >= t.size() && name.compare(name.size() - t.size(), t.size(), t) == 0;
    };
    return ((name.rfind("trial_pair_", 0) == 0 || name.rfind("sweeps_", 0) == 0) &&
            endsWith(".csv")) ||
           endsWith(".json.partial");
}

bool holdsRun(const std::string& dir) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (isRunArtefact(it->path().filename().string())) return true;
    return false;
}

std::optional<RunManifest> readRunManifest(const std::string& dir) {
    const fs::path path = fs::path(dir) / kManifest;
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;
    const std::string file = path.string();
    const Json j = readJsonFile(file);
    JsonFields f(j, file, "");
    RunManifest m;
    m.runId = f.text("run_id");
    m.command = f.text("command", "");
    m.experiment = f.text("experiment", "");
    m.started = f.text("started", "");
    m.facts.samplesPerTap = f.integer("samples_per_tap", 0, 1000000, 0);
    m.facts.taxels = f.integer("taxels", 0, 100000, 0);
    m.facts.stageTravel_mm = f.point("stage_travel_mm", Vec2{0, 0});
    m.finished = f.flag("finished", false);
    if (f.has("files")) {
        const Json& list = f.raw("files");
        if (!list.is_object())
            f.fail("files", "expected the run's files with their sizes; the manifest is damaged");
        for (auto it = list.begin(); it != list.end(); ++it) m.files[it.key()] = stampOf(it, file);
    }
    return m;
}

std::string runIdOf(const std::string& dir) {
    try {
        const auto m = readRunManifest(dir);
        return m ? m->runId : std::string();
    } catch (const InputError&) {
        return {};
    }
}

std::string claimRunFolder(const std::string& dir, const std::string& command,
                           const std::string& experiment, const RunFacts& facts, bool replace) {
    if (holdsRun(dir)) {
        if (!replace) {
            std::string whose;
            try {
                if (const auto m = readRunManifest(dir))
                    whose = " (" + m->command + " of '" + m->experiment + "', started " +
                            m->started + ")";
            } catch (const InputError&) {
                whose = " (its run.json is damaged)";
            }
            throw InputError(dir, "",
                             "this folder already holds a run" + whose +
                                 "; give another output folder, or ask to replace that run "
                                 "(--replace), which removes its files first");
        }
        std::error_code ec;
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
            if (!isRunArtefact(it->path().filename().string())) continue;
            std::error_code removed;
            fs::remove_all(it->path(), removed);
            if (removed)
                throw InputError(it->path().string(), "",
                                 "cannot remove this file of the run being replaced (" +
                                     removed.message() +
                                     "); remove it yourself or choose another output folder");
        }
    }
    ensureOutputDirectory(dir);
    RunManifest m;
    m.runId = newRunId();
    m.command = command;
    m.experiment = experiment;
    m.started = isoNow();
    m.facts = facts;
    writeJsonAtomically((fs::path(dir) / kManifest).string(), manifestJson(m));
    return m.runId;
}

RunFolderClaim::RunFolderClaim(std::string dir, const std::string& command,
                               const std::string& experiment, const RunFacts& facts, bool replace)
    : dir_(std::move(dir)) {
    claimRunFolder(dir_, command, experiment, facts, replace);
}

RunFolderClaim::~RunFolderClaim() {
    finishRunFolder(dir_);
}

RunFacts runFactsOf(const ExperimentSpec& spec, const std::vector<CollectedTap>* recorded) {
    RunFacts facts;
    const bool fromRecording = recorded && !recorded->empty();
    facts.samplesPerTap =
        fromRecording ? recorded->front().record.tap.sampleCount() : spec.scene.tap.samples;
    facts.taxels = fromRecording ? recorded->front().record.tap.taxels
                                 : static_cast<int>(spec.scene.fingertip.taxels.size());
    facts.stageTravel_mm = spec.scene.stage.travel_mm;
    return facts;
}

void finishRunFolder(const std::string& dir) noexcept {
    try {
        auto m = readRunManifest(dir);
        if (!m) return;
        m->finished = true;
        m->files = artefactsIn(dir, true);
        writeJsonAtomically((fs::path(dir) / kManifest).string(), manifestJson(*m));
    } catch (...) {
        // The manifest stays unfinished: readers then check what they can.
    }
}

void checkOneRun(const std::string& dir, const std::vector<std::string>& read, std::string* note) {
    const auto m = readRunManifest(dir);
    if (!m) {
        if (note)
            *note = dir + " has no run.json, so nothing shows that its files come from one run";
        return;
    }
    const std::string manifest = (fs::path(dir) / kManifest).string();
    // A summary of another run beside this run's data.
    const fs::path summary = fs::path(dir) / "summary.json";
    std::error_code ec;
    if (fs::exists(summary, ec)) {
        const Json s = readJsonFile(summary.string());
        const std::string id = s.is_object() && s.contains("run_id") && s["run_id"].is_string()
                                   ? s["run_id"].get<std::string>()
                                   : "";
        if (id != m->runId)
            throw InputError(summary.string(), "/run_id",
                             "this summary belongs to " +
                                 (id.empty() ? std::string("a run without an id") : "run " + id) +
                                 ", not to run " + m->runId + " that " + manifest +
                                 " names: the folder mixes two runs' files; rerun into an empty "
                                 "folder");
    }
    if (!m->finished) return;  // stopped before listing its files: its tables end where it did
    const auto present = artefactsIn(dir, false);
    for (const auto& [name, stamp] : present) {
        const std::string path = (fs::path(dir) / name).string();
        const auto listed = m->files.find(name);
        if (listed == m->files.end())
            throw InputError(path, "",
                             "this file is not one of run " + m->runId + "'s (" + manifest +
                                 " lists the run's files): the folder mixes two runs' files; "
                                 "rerun into an empty folder or remove it");
        if (listed->second.bytes != stamp.bytes)
            throw InputError(path, "",
                             "this file has " + std::to_string(stamp.bytes) + " bytes but run " +
                                 m->runId + " left it with " +
                                 std::to_string(listed->second.bytes) + " (" + manifest +
                                 "): it was written to since, perhaps by another run; rerun into "
                                 "an empty folder");
        if (!listed->second.sha256.empty() && sha256OfFile(path) != listed->second.sha256)
            throw InputError(path, "",
                             "this file's SHA-256 differs from the one run " + m->runId +
                                 " recorded in " + manifest +
                                 ": it was changed since the run wrote it; rerun into an empty "
                                 "folder");
    }
    for (const std::string& name : read)
        if (m->files.count(name) == 0)
            throw InputError((fs::path(dir) / name).string(), "",
                             "run " + m->runId + " did not write this file (" + manifest +
                                 " lists the run's files)");
}

void checkProvenRun(const std::string& dir, const std::string& file) {
    // The file itself first: a pipe or a device in its place is named as such.
    openInputFile((fs::path(dir) / file).string());
    const std::string manifest = (fs::path(dir) / kManifest).string();
    const auto m = readRunManifest(dir);
    if (!m)
        throw InputError(manifest, "",
                         "there is no run.json, so nothing proves " + file +
                             " is the run's own; use the folder a run wrote, whole");
    if (!m->finished)
        throw InputError(manifest, "/finished",
                         "the run did not finish listing its files (it was stopped or killed), "
                         "so its " +
                             file + " cannot be proven whole; run it again");
    checkOneRun(dir, {file});
    if (const auto listed = m->files.find(file); listed->second.sha256.empty())
        throw InputError(manifest, "/files/" + file,
                         "records only the size of " + file +
                             ", as folders written before digests were kept do, so it cannot be "
                             "proven whole; run that shard again");
}

std::optional<std::string> runFolderOf(const std::string& recording) {
    std::error_code ec;
    const fs::path p = fs::absolute(recording, ec).lexically_normal();
    if (p.parent_path().filename() != "data") return std::nullopt;
    return p.parent_path().parent_path().string();
}

RecordingBounds checkedRecordingBounds(const std::string& recording, std::string* note) {
    RecordingBounds bounds;
    const auto dir = runFolderOf(recording);
    if (!dir) return bounds;
    std::error_code ignored;
    const std::string relative = fs::absolute(recording, ignored)
                                     .lexically_normal()
                                     .lexically_relative(*dir)
                                     .generic_string();
    checkOneRun(*dir, {relative}, note);
    if (const auto m = readRunManifest(*dir)) {
        bounds.samplesPerTap = m->facts.samplesPerTap;
        bounds.taxels = m->facts.taxels;
        bounds.taxelsFrom = "its run (" + (fs::path(*dir) / kManifest).string() + ")";
        if (m->facts.stageTravel_mm.x > 0 && m->facts.stageTravel_mm.y > 0)
            bounds.travel_mm = m->facts.stageTravel_mm;
    }
    return bounds;
}

}  // namespace activetouch
