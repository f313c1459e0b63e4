#pragma once
// Loading the files a run starts from, with every check the run itself would make, so that a
// bad file is refused (by file, place and problem) before any tap: the one entry the command
// line, the window and the fuzzing harnesses read experiment and scene files through.
#include <string>

#include "core/experiment/Experiment.h"
#include "core/run/SimulatedRigs.h"

namespace activetouch {

/// Loads an experiment (with "extends" resolved) or, unless `requireExperiment`, a bare scene,
/// and checks everything a run would check, the scene's effects included (as `rigs` would
/// simulate them). With `document`, an experiment's document with "extends" resolved is given
/// there too (what the window's panels show and save). Throws InputError.
ExperimentSpec loadCheckedExperiment(const std::string& path, bool requireExperiment,
                                     const SimulatedRigs& rigs, Json* document = nullptr);

}  // namespace activetouch
