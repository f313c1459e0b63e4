#pragma once
// An experiment file's "sweeps" section (docs/accuracy-vs-time.md), read for parseExperiment.
#include "core/experiment/Experiment.h"
#include "core/io/JsonFields.h"

namespace activetouch {

/// Reads `f` (the "sweeps" object) into e.sweeps; throws InputError by place.
void parseSweeps(const JsonFields& f, ExperimentSpec& e);

}  // namespace activetouch
