#pragma once
// Run options for a run on the simulated rig, as the window and the command line give them.
#include "core/run/ExperimentRun.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch::test {

inline RunOptions onSimulatedRig() {
    RunOptions options;
    options.simulated = &simulatedRigs();
    return options;
}

}  // namespace activetouch::test
