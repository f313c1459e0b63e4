#include "core/run/TrialRecognition.h"

#include <algorithm>

#include "core/recognition/PoseRecognition.h"
#include "core/recognition/ShapeRecognition.h"
#include "core/stats/Intervals.h"

namespace activetouch {

void summarisePathAngles(RunResult& result) {
    std::vector<double> angleErrors;
    for (const TrialRun& run : result.trials)
        for (const FollowedTap& t : run.result.taps)
            if (t.angleError_deg >= 0.0) angleErrors.push_back(t.angleError_deg);
    result.pathAngleTaps = static_cast<int>(angleErrors.size());
    result.pathMedianAngleError_deg = stats::medianOr(angleErrors, -1.0);
}

namespace {

/// Each distinct object the experiment follows (its first trial's label) at the pose the
/// experiment states for it: where and turned as the file places it, or, where each trial draws
/// its own turn, unturned (the shape's own frame). Never a pose a trial drew.
std::vector<std::pair<std::string, Polygon>> statedOutlines(const ExperimentSpec& spec) {
    std::vector<std::pair<std::string, Polygon>> outlines;
    for (const TrialSpec& ts : spec.trials) {
        const bool known = std::any_of(outlines.begin(), outlines.end(),
                                       [&](const auto& o) { return o.first == ts.label; });
        if (known) continue;
        ObjectSpec stated = ts.object;
        if (stated.rotationDrawn) stated.rotationDeg = 0.0;
        outlines.emplace_back(ts.label, stated.outline());
    }
    return outlines;
}

}  // namespace

void recogniseTrialPaths(RunResult& result) {
    const ExperimentSpec& spec = result.spec;
    // The paper's rule: templates at the centre of the valid range, one per distinct object, at
    // the pose the experiment states (statedOutlines), so that no trial hands it its own turn.
    const auto outlines = statedOutlines(spec);
    std::vector<NamedOutline> shapes;
    for (const auto& [label, outline] : outlines) shapes.push_back({label, &outline});
    result.templates = shapeTemplates(
        shapes, 0.5 * (result.validOffsets.low + result.validOffsets.high),
        spec.following.followStep_mm, spec.recognition.bins, spec.recognition.smoothingSigmaBins);
    // At any pose: one template per distinct shape, in the shape's own frame.
    result.poseTemplates.clear();
    const double centreOffset = 0.5 * (result.validOffsets.low + result.validOffsets.high);
    for (const TrialSpec& ts : spec.trials) {
        const bool known = std::any_of(result.poseTemplates.begin(), result.poseTemplates.end(),
                                       [&](const PoseTemplate& t) { return t.shape == ts.label; });
        if (known) continue;
        ObjectSpec own = ts.object;
        own.rotationDeg = 0.0;
        own.offset = {};
        result.poseTemplates.push_back(poseTemplate(ts.label, own.outline(), centreOffset));
    }
    int recognised = 0, correct = 0, correctSmoothed = 0, correctAnyPose = 0;
    std::vector<double> turnErrors, placeErrors;
    for (TrialRun& run : result.trials) {
        if (run.result.mode != spec.recognition.ofMode) continue;
        run.recognised = true;
        const std::vector<Vec2> path = run.result.path();
        run.recognition = recognise(path, result.templates, spec.recognition.smoothingSigmaBins);
        run.poseRecognition = recognisePose(path, result.poseTemplates);
        for (const PoseTemplate& tpl : result.poseTemplates)
            if (tpl.shape == run.label)
                run.objectCentre = run.objectOffset + rotated(tpl.centroid, run.rotationDeg);
        ++recognised;
        correct += run.recognition.predicted == run.label;
        correctSmoothed += run.recognition.predictedSmoothed == run.label;
        const PoseRecognition& pose = run.poseRecognition;
        if (pose.valid && pose.predicted == run.label) {
            ++correctAnyPose;
            if (pose.best.symmetry != 0)
                turnErrors.push_back(
                    rotationErrorDeg(pose.best.rotationDeg, run.rotationDeg, pose.best.symmetry));
            placeErrors.push_back(distance(pose.best.position, run.objectCentre));
        }
    }
    if (recognised > 0) {
        result.recognitionAccuracy = double(correct) / recognised;
        result.recognitionAccuracySmoothed = double(correctSmoothed) / recognised;
        result.recognitionAccuracyAnyPose = double(correctAnyPose) / recognised;
    }
    result.medianRotationError_deg = stats::medianOr(turnErrors, 0.0);
    result.medianPositionError_mm = stats::medianOr(placeErrors, 0.0);
}

}  // namespace activetouch
