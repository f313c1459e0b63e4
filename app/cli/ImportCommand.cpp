#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/CliSupport.h"
#include "app/cli/Commands.h"
#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/experiment/Experiment.h"
#include "core/records/DumperLog.h"
#include "core/records/TapCsv.h"
#include "core/records/TapCutting.h"
#include "core/run/OutputFiles.h"
#include "core/run/RunFolder.h"

namespace activetouch::cli {

namespace fs = std::filesystem;

namespace {

/// A finite number within lo..hi from an option's text, or nothing.
std::optional<double> optionNumber(const std::string& text, double lo, double hi) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(v) || v < lo || v > hi)
        return std::nullopt;
    return v;
}

/// How the experiment's taps are cut from a skin log: its tap's samples and rate, the reflex
/// threshold (the scene's, or --threshold) and the lead before a crossing (the descent, or
/// --lead-frames). Empty, or what is wrong with an option.
std::string cuttingOf(const ExperimentSpec& spec, const RunArguments& parsed, TapCutting& cutting) {
    const TapSpec& tapSpec = spec.scene.tap;
    cutting.samplesPerTap = tapSpec.samples;
    cutting.sampleRate_hz = tapSpec.sampleRate_hz;
    cutting.reflexThreshold = tapSpec.contactThreshold;
    cutting.leadFrames =
        static_cast<int>(std::ceil((tapSpec.retractHeight_mm - spec.scene.object.height_mm) /
                                   tapSpec.descentSpeed_mm_s * tapSpec.sampleRate_hz));
    if (!parsed.text("--threshold").empty()) {
        const auto v = optionNumber(parsed.text("--threshold"), 1e-9, 255.0 * kMaxTaxels);
        if (!v) return "--threshold takes a total pressure in counts above 0";
        cutting.reflexThreshold = *v;
    }
    if (!parsed.text("--lead-frames").empty()) {
        const auto v = optionNumber(parsed.text("--lead-frames"), 0, tapSpec.samples - 1);
        if (!v || *v != std::floor(*v))
            return "--lead-frames takes a whole number of frames, 0 to " +
                   std::to_string(tapSpec.samples - 1);
        cutting.leadFrames = static_cast<int>(*v);
    }
    return {};
}

}  // namespace

namespace {

/// What an import reads, every part checked before anything is written.
struct Imported {
    TaxelMap map;
    SkinStream stream;
    std::vector<CollectedTap> taps;
    std::string cutOff;  ///< the last tap, where the log ends inside it
};

Imported readImported(const ExperimentSpec& spec, const RunArguments& parsed,
                      const TapCutting& cutting) {
    const std::string posePath = parsed.text("--poses");
    Imported in;
    in.map = readTaxelMap(parsed.text("--taxel-map"),
                          static_cast<int>(spec.scene.fingertip.taxels.size()));
    in.stream = readDumperLog(parsed.recordingPath, in.map);
    checkMapReadsTheTouch(in.stream, in.map, parsed.text("--taxel-map"));
    RecordingBounds bounds;
    bounds.travel_mm = spec.scene.stage.travel_mm;
    std::vector<PoseLogEntry> poses;
    if (!posePath.empty()) poses = readPoseLog(posePath, bounds);
    const std::vector<TapRecord> cut = cutTaps(in.stream, posePath.empty() ? nullptr : &poses,
                                               cutting, in.stream.source, posePath, &in.cutOff);
    in.taps = labelProtocolTaps(cut, !posePath.empty(), poses, spec.scene.object.outline(),
                                spec.classes, spec.training, posePath, in.stream.source);
    const std::int64_t planned = spec.plannedTaps();
    if (posePath.empty() && static_cast<std::int64_t>(in.taps.size()) != planned)
        throw InputError(in.stream.source, "",
                         "the reflex threshold (" + numberText(cutting.reflexThreshold) +
                             " counts) finds " + std::to_string(in.taps.size()) +
                             " taps, but the experiment's protocol takes " +
                             std::to_string(planned) +
                             ": taps that touch nothing leave no trace in a skin log, so without "
                             "the stage's pose log (--poses) the taps cannot be matched to their "
                             "classes");
    return in;
}

/// import.json: where the taps came from and how they were cut.
Json importRecord(const ExperimentSpec& spec, const RunArguments& parsed, const Imported& in,
                  const TapCutting& cutting, int reflex) {
    const std::string posePath = parsed.text("--poses");
    return {
        {"experiment", spec.name},
        {"skin_log", parsed.recordingPath},
        {"taxel_map", parsed.text("--taxel-map")},
        {"values_per_frame", in.map.valuesPerFrame},
        {"taxel_values", in.map.valueOf},
        {"stamps_per_line", in.stream.stamps},
        {"frames", in.stream.frameCount()},
        {"frames_missing", in.stream.framesMissing},
        {"cut_by", posePath.empty() ? "reflex threshold" : "pose log"},
        {"pose_log", posePath.empty() ? Json() : Json(posePath)},
        {"reflex_threshold_counts", cutting.reflexThreshold},
        {"lead_frames", posePath.empty() ? Json(cutting.leadFrames) : Json()},
        {"samples_per_tap", cutting.samplesPerTap},
        {"taps", in.taps.size()},
        {"taps_planned", spec.plannedTaps()},
        {"taps_on_the_reflex", reflex},
        {"cut_off", in.cutOff.empty() ? Json() : Json(in.cutOff)},
    };
}

}  // namespace

/// import: a skin log from YARP's data dumper (with a taxel map and, where there is one, the
/// stage's pose log) as the tap recording of an experiment's training protocol.
int commandImport(const std::vector<std::string>& args) {
    const RunArguments parsed =
        parseRunArguments(args, "import", {}, false, true,
                          {{"--taxel-map", "a taxel map file"},
                           {"--poses", "a pose log"},
                           {"--threshold", "the reflex threshold in counts"},
                           {"--lead-frames", "a number of frames"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    if (parsed.text("--taxel-map").empty())
        return usageError(
            "import needs --taxel-map <file>: which of the log's values are the fingertip's "
            "taxels (docs/file-formats.md)");
    const auto loaded = loadForRun(parsed.experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    TapCutting cutting;
    if (const std::string problem = cuttingOf(spec, parsed, cutting); !problem.empty())
        return usageError(problem);
    const std::string outDir = parsed.outDir.empty()
                                   ? (fs::path("results") / (spec.name + "_import")).string()
                                   : parsed.outDir;
    try {
        const Imported in = readImported(spec, parsed, cutting);
        const auto claimed =
            claimOrSay(outDir, "import", spec, runFactsOf(spec, &in.taps), parsed.replace);
        if (!claimed) return kBadInput;
        ensureOutputDirectory((fs::path(outDir) / "data").string());
        const std::string tapsPath = (fs::path(outDir) / "data" / "taps.csv").string();
        {
            TapCsvWriter writer(tapsPath, static_cast<int>(in.map.valueOf.size()));
            for (const CollectedTap& t : in.taps) writer.append(t, spec.classes);
        }
        int reflex = 0;
        for (const CollectedTap& t : in.taps) reflex += t.record.ending == TapEnding::ContactReflex;
        writeJsonAtomically((fs::path(outDir) / "import.json").string(),
                            importRecord(spec, parsed, in, cutting, reflex));
        std::printf(
            "%s: %zu frames (%lld missing by the counter) from %s, %zu taps cut by the %s (%d "
            "reached the reflex threshold of %g counts) of the %lld the protocol takes\n",
            spec.name.c_str(), in.stream.frameCount(),
            static_cast<long long>(in.stream.framesMissing), parsed.recordingPath.c_str(),
            in.taps.size(), parsed.text("--poses").empty() ? "reflex threshold" : "pose log",
            reflex, cutting.reflexThreshold, static_cast<long long>(spec.plannedTaps()));
        if (!in.cutOff.empty()) std::printf("%s\n", in.cutOff.c_str());
        std::printf("wrote %s; analyse it with: activetouch-cli analyse %s %s\n", tapsPath.c_str(),
                    parsed.experimentPath.c_str(), tapsPath.c_str());
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "import failed: %s\n", e.what());
        return kRunFailed;
    }
}

/// dump: a recording's training and test taps written as YARP's data dumper would have logged
/// them (for yarpdataplayer, or to try an import), with the stage's pose log beside.
int commandDump(const std::vector<std::string>& args) {
    const RunArguments parsed =
        parseRunArguments(args, "dump", {}, false, true, {{"--taxel-map", "a taxel map file"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    if (parsed.text("--taxel-map").empty() || parsed.outDir.empty())
        return usageError("dump needs --taxel-map <file> and --out <folder>");
    const auto loaded = loadForRun(parsed.experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    try {
        const TaxelMap map = readTaxelMap(parsed.text("--taxel-map"),
                                          static_cast<int>(spec.scene.fingertip.taxels.size()));
        std::string cutOff;
        const auto taps = readTapCsv(parsed.recordingPath, spec.classes, &cutOff,
                                     checkedRecordingBounds(parsed.recordingPath));
        if (fs::exists(fs::path(parsed.outDir) / "data.log") && !parsed.replace)
            throw InputError(parsed.outDir, "",
                             "already holds a data.log; choose another folder, or give --replace");
        std::vector<TapRecord> records;
        records.reserve(taps.size());
        for (const CollectedTap& t : taps) records.push_back(t.record);
        writeDumperLog(parsed.outDir, records, map, spec.scene.tap.sampleRate_hz);
        std::printf(
            "%zu taps of %s written to %s/data.log (%d values a frame), with info.log and "
            "poses.log\n",
            records.size(), parsed.recordingPath.c_str(), parsed.outDir.c_str(),
            map.valuesPerFrame);
        if (!cutOff.empty()) std::printf("left out: %s\n", cutOff.c_str());
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dump failed: %s\n", e.what());
        return kRunFailed;
    }
}

}  // namespace activetouch::cli
