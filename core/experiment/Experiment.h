#pragma once
// An experiment file: a scene plus the protocol to run on it (DESIGN.md §4). The paper's
// experiment is experiments/paper.json.
#include <optional>
#include <string>

#include "core/classify/HistogramClassifier.h"
#include "core/scene/Scene.h"
#include "core/tap/ClassSet.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

struct ExperimentSpec {
    std::string source;
    std::string name;
    std::string description;
    SceneSpec scene;
    ClassSet classes;
    ClassifierSettings classifier;
    TrainingProtocolSettings training;
    int validRangeWidth = 4;  ///< positions in the valid range window
};

/// Parses an experiment; the scene may be inline or a path relative to the experiment file.
ExperimentSpec parseExperiment(const Json& json, const std::string& source, const std::string& baseDirectory);
ExperimentSpec loadExperiment(const std::string& path);

/// Whether a JSON file is an experiment (has "scene") or a bare scene.
bool looksLikeExperiment(const Json& json);

}  // namespace activetouch
