// Scene files (and anything else `check` reads as JSON) through the command line's entry.
#include "core/run/ExperimentFiles.h"
#include "core/common/InputError.h"
#include "devices/simulated/SimulatedWorld.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("scene.json", data, size);
    try {
        loadCheckedExperiment(path, false, simulatedRigs());
    } catch (const InputError&) {
    }
    return 0;
}
