#pragma once
// Running an experiment end to end on the simulated rig and writing its artefacts
// (DESIGN.md §4): summary.json, data/*.csv (taps appended as they are taken), and the tables
// behind every figure. Figures are drawn by app/figures from the same result.
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/classify/HistogramClassifier.h"
#include "core/experiment/Experiment.h"
#include "core/validation/OfflineValidation.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

struct RunProgress {
    int tapsDone = 0;
    int tapsPlanned = 0;
    std::string step;
};

struct RunResult {
    ExperimentSpec spec;            ///< with the seed actually used
    ClassSet classes;               ///< with the region map
    std::vector<std::string> activeEffects;
    std::vector<CollectedTap> taps; ///< every tap, in order
    HistogramClassifier classifier;
    ValidationResult validation;
    bool cancelled = false;
    double robotTime_s = 0.0;
    std::uint64_t tapsSimulated = 0;
    double runWall_s = 0.0;         ///< simulation, training and validation
};

struct RunOptions {
    std::string outDir;               ///< empty: write nothing
    std::optional<std::uint64_t> seed;
    std::function<void(const RunProgress&)> progress;
    const std::atomic<bool>* cancel = nullptr;
};

/// Runs the experiment's steps. Taps are appended to <outDir>/data/taps.csv as they are taken.
/// Throws RigError if a device fails and InputError if the output cannot be written.
RunResult runExperiment(const ExperimentSpec& spec, const RunOptions& options);

/// Writes the tables (data/*.csv) of a finished run.
void writeRunTables(const RunResult& result, const std::string& outDir);

/// Writes <outDir>/summary.json atomically; `timing` adds keys under "timing".
void writeSummary(const RunResult& result, const std::string& outDir, double wall_s, double figures_s);

/// The summary document itself (what writeSummary writes).
Json summaryJson(const RunResult& result, double wall_s, double figures_s);

}  // namespace activetouch
