#include "core/experiment/Experiment.h"

#include <filesystem>

namespace activetouch {
namespace fs = std::filesystem;

bool looksLikeExperiment(const Json& json) { return json.is_object() && json.contains("scene"); }

ExperimentSpec parseExperiment(const Json& json, const std::string& source, const std::string& baseDirectory) {
    JsonFields f(json, source, "");
    f.rejectUnknownKeys({"name", "description", "scene", "seed", "classes", "classifier", "training", "validation"});
    ExperimentSpec e;
    e.source = source;
    e.name = f.text("name");
    e.description = f.text("description", "");
    if (!f.has("scene")) f.fail("scene", "missing 'scene': a scene object or the path of a scene file");
    const Json& scene = f.raw("scene");
    if (scene.is_string()) {
        fs::path p(scene.get<std::string>());
        if (p.is_relative()) p = fs::path(baseDirectory) / p;
        if (!fs::exists(p)) f.fail("scene", "scene file '" + p.string() + "' does not exist; check the path (relative to the experiment file)");
        e.scene = loadScene(p.string());
    } else {
        e.scene = parseScene(scene, source, "/scene", baseDirectory);
    }
    if (f.has("seed")) e.scene.seed = static_cast<std::uint64_t>(f.integer("seed", 0, 2147483647L));

    if (f.has("classes")) {
        const JsonFields c = f.object("classes");
        c.rejectUnknownKeys({"orientations_deg", "positions", "position_step_mm"});
        if (c.has("orientations_deg")) {
            e.classes.orientationsDeg = c.numbers("orientations_deg", -360.0, 360.0);
            if (e.classes.orientationsDeg.empty()) c.fail("orientations_deg", "list at least one orientation");
        }
        e.classes.positions = c.integer("positions", 2, 200, e.classes.positions);
        e.classes.positionStep_mm = c.number("position_step_mm", 0.05, 10.0, e.classes.positionStep_mm);
    }
    if (f.has("classifier")) {
        const JsonFields c = f.object("classifier");
        c.rejectUnknownKeys({"bins", "smoothing"});
        e.classifier.bins = c.integer("bins", 1, 100000, e.classifier.bins);
        e.classifier.smoothing = c.number("smoothing", 1e-12, 1e6, e.classifier.smoothing);
    }
    if (f.has("training")) {
        const JsonFields t = f.object("training");
        t.rejectUnknownKeys({"data_sets", "training_sets", "taps_per_class", "test_offset_mm", "placement_jitter_mm"});
        e.training.dataSets = t.integer("data_sets", 2, 1000, e.training.dataSets);
        if (t.has("training_sets")) {
            e.training.trainingSets.clear();
            for (double s : t.numbers("training_sets", 1, 1000)) e.training.trainingSets.push_back(static_cast<int>(s));
        }
        e.training.tapsPerClass = t.integer("taps_per_class", 1, 1000, e.training.tapsPerClass);
        e.training.testOffset_mm = t.number("test_offset_mm", -5.0, 5.0, e.training.testOffset_mm);
        e.training.placementJitter_mm = t.number("placement_jitter_mm", 0.0, 5.0, e.training.placementJitter_mm);
        if (auto p = e.training.problem(); !p.empty()) throw InputError(source, "/training", p);
    }
    if (f.has("validation")) {
        const JsonFields v = f.object("validation");
        v.rejectUnknownKeys({"valid_range_positions"});
        e.validRangeWidth = v.integer("valid_range_positions", 1, e.classes.positions, e.validRangeWidth);
    }
    // The training object must offer an edge for every orientation.
    try {
        edgeSites(e.scene.object.outline(), e.classes);
    } catch (const std::invalid_argument& err) {
        throw InputError(source, "/classes/orientations_deg", err.what());
    }
    return e;
}

ExperimentSpec loadExperiment(const std::string& path) {
    const Json j = readJsonFile(path);
    if (!looksLikeExperiment(j))
        throw InputError(path, "/", "this is not an experiment file (it has no 'scene'); run an experiment, or use 'check' for a scene");
    return parseExperiment(j, path, fs::path(path).parent_path().string());
}

}  // namespace activetouch
