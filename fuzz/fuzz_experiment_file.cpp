// Experiment files through the command line's entry (loadCheckedExperiment), "extends" included:
// the input may extend base.json, a small valid experiment beside it.
#include "core/run/ExperimentFiles.h"
#include "core/common/InputError.h"
#include "devices/simulated/SimulatedWorld.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    const std::string base = R"({"name": "base", "scene": {"object": {"shape": "rectangle",
        "width_mm": 48, "height_mm": 58}, "seed": 3}, "classes": {"positions": 6},
        "training": {"data_sets": 2}})";
    fuzz::writeFile("base.json", base.data(), base.size());
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("experiment.json", data, size);
    try {
        loadCheckedExperiment(path, true, simulatedRigs());
    } catch (const InputError&) {
    }
    return 0;
}
