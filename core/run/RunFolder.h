#pragma once
// A run folder belongs to one run (docs/limits.md, "Output folders"). Before a command writes
// anything it claims the folder: a folder that already holds a run is refused unless the user
// asked to replace it, and replacing removes every file of the old run first, so no two runs'
// files ever mix. The claim is <dir>/run.json, written first: the run's id, the command, the
// experiment and the facts a recording is checked against (samples per tap, taxels, stage
// travel). When the command ends, however it ends, run.json is completed with every file the
// run left and its size; readers (replay, analyse, check) use it to refuse files of another run.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/Vec2.h"
#include "core/io/Csv.h"

namespace activetouch {

/// What a run's recordings must agree with.
struct RunFacts {
    int samplesPerTap = 0, taxels = 0;
    Vec2 stageTravel_mm{0, 0};
};

/// What a run's manifest records of one of its files.
struct FileStamp {
    std::uintmax_t bytes = 0;
    std::string sha256;  ///< 64 hex digits
    bool operator==(const FileStamp&) const = default;
};

struct RunManifest {
    std::string runId, command, experiment, started;
    RunFacts facts;
    bool finished = false;  ///< the command ended and listed its files
    std::map<std::string, FileStamp> files;  ///< relative path -> size and digest, once finished
};

/// The names a run writes in its folder: run.json, the documents and tables at the top and the
/// data/ and figures/ folders. Anything else in the folder is the user's and is never touched.
bool isRunArtefact(const std::string& topLevelName);

/// Whether `dir` holds a run: a run.json, or any run artefact.
bool holdsRun(const std::string& dir);

/// Claims `dir` for a new run of `command` (run, seeds, compare, analyse, replay): refused with
/// an InputError naming the folder and what to do if it holds a run and `replace` is false; with
/// `replace`, every run artefact in it is removed first. Writes <dir>/run.json and returns the
/// new run's id.
std::string claimRunFolder(const std::string& dir, const std::string& command,
                           const std::string& experiment, const RunFacts& facts, bool replace);

/// Claims a folder as claimRunFolder does (throwing as it does) and, when it goes out of scope,
/// completes the folder's run.json however the run ended.
class RunFolderClaim {
public:
    RunFolderClaim(std::string dir, const std::string& command, const std::string& experiment,
                   const RunFacts& facts, bool replace);
    ~RunFolderClaim();
    RunFolderClaim(const RunFolderClaim&) = delete;
    RunFolderClaim& operator=(const RunFolderClaim&) = delete;

private:
    std::string dir_;
};

/// The facts of a run of `spec`; with `recorded` taps (an analysis), the recording's.
struct CollectedTap;
struct ExperimentSpec;
RunFacts runFactsOf(const ExperimentSpec& spec, const std::vector<CollectedTap>* recorded = nullptr);

/// Completes <dir>/run.json with every run artefact now in `dir`, its size and SHA-256. Throws
/// nothing:
/// a folder that cannot be listed keeps its unfinished manifest.
void finishRunFolder(const std::string& dir) noexcept;

/// The manifest of `dir`, or nothing if it has none. Throws InputError for one that cannot be
/// read.
std::optional<RunManifest> readRunManifest(const std::string& dir);

/// The run id of `dir`'s manifest, or empty.
std::string runIdOf(const std::string& dir);

/// Refuses files in `dir` that are not the run's its manifest names: with a finished manifest,
/// a file it does not list, or one whose size or SHA-256 differs
/// (written to since, by another run, or by hand); a summary.json of another run id. `read` are the files (relative to `dir`) the caller is about
/// to read. A folder without a manifest passes (a recording from elsewhere) and `note` says so.
void checkOneRun(const std::string& dir, const std::vector<std::string>& read,
                 std::string* note = nullptr);

/// Refuses, as checkOneRun does, a folder of `command` (seeds, compare, merge) whose files are
/// not its run's, and also one without a finished run.json that records `file`'s digest: only a
/// run that ended and listed its files can be proven whole.
void checkProvenRun(const std::string& dir, const std::string& file);

/// The run folder a recording lies in: <dir> for <dir>/data/<file>.csv, else nothing.
std::optional<std::string> runFolderOf(const std::string& recording);

/// What the recording at `recording` is held to: its run's samples per tap and stage travel
/// where a run.json beside it gives them, else the general bounds. First checks, as checkOneRun
/// does, that the recording is its run's. `note` as for checkOneRun.
RecordingBounds checkedRecordingBounds(const std::string& recording, std::string* note = nullptr);

}  // namespace activetouch
