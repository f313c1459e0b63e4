#pragma once
// What a finished run leaves in its folder besides the taps recorded as they were taken
// (docs/file-formats.md): the tables behind every figure under data/, and summary.json.
#include <chrono>
#include <functional>
#include <string>

#include "core/io/JsonFields.h"
#include "core/io/OutputFile.h"
#include "core/run/ExperimentRun.h"

namespace activetouch {

/// The columns each tap of a trial has in following_paths.csv, after the trial's own.
inline constexpr const char* kTrialTapColumns =
    "tap,x_mm,y_mm,shape_class,orientation_deg,position,rule,move_x_mm,move_y_mm,progress_mm,"
    "contour_distance_mm";
/// Appends a row per tap of `t` to `f`: `prefix` (the row's leading columns, ending in a comma),
/// then the kTrialTapColumns.
void printTrialTaps(OutputFile& f, const std::string& prefix, const TrialRun& t);

/// Writes the tables (data/*.csv) of a finished run.
void writeRunTables(const RunResult& result, const std::string& outDir);

/// Writes <outDir>/summary.json atomically; `timing` adds keys under "timing".
void writeSummary(const RunResult& result, const std::string& outDir, double wall_s,
                  double figures_s);

/// The summary document itself (what writeSummary writes).
Json summaryJson(const RunResult& result, double wall_s, double figures_s);

struct ArtefactTiming {
    double wall_s = 0.0;     ///< since the run started, figures included
    double figures_s = 0.0;  ///< drawing and exporting the figures
};

/// Writes what a finished run leaves besides its recordings, as the window and the command line
/// both do: the tables, then the figures `drawFigures` writes (if given; it returns the seconds
/// it took), then summary.json last, with the wall time since `started`.
ArtefactTiming writeRunArtefacts(const RunResult& result, const std::string& outDir,
                                 std::chrono::steady_clock::time_point started,
                                 const std::function<double()>& drawFigures = {});

}  // namespace activetouch
