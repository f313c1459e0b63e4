#include "core/run/ExperimentFiles.h"

#include <filesystem>

#include "core/io/JsonText.h"

namespace activetouch {

ExperimentSpec loadCheckedExperiment(const std::string& path, bool requireExperiment,
                                     const SimulatedRigs& rigs, Json* document) {
    const Json j = readJsonFile(path);
    ExperimentSpec spec;
    if (looksLikeExperiment(j)) {
        Json resolved = readExperimentFile(path);
        spec = parseExperiment(resolved, path, std::filesystem::path(path).parent_path().string());
        if (document) *document = std::move(resolved);
    } else if (requireExperiment) {
        throw InputError(
            path, "/",
            "this is not an experiment file (it has neither 'scene' nor 'extends'); give an "
            "experiment such as experiments/paper.json");
    } else {
        spec.scene =
            parseScene(j, path, "", std::filesystem::path(path).parent_path().string());
    }
    rigs.checkEffects(spec.scene);
    return spec;
}

}  // namespace activetouch
