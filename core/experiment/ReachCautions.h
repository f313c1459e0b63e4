#pragma once
// Where an experiment's objects have features the fingertip cannot resolve (notches, teeth,
// sharp corners smaller than its contact patch; core/geometry/ContourReach.h): `check`, `run`
// and the window say so before any tap.
#include <string>
#include <vector>

#include "core/experiment/Experiment.h"
#include "core/geometry/ContourReach.h"

namespace activetouch {

/// The contact patch of `scene`'s fingertip on an edge, as a radius, mm
/// (FingertipContactModel::edgeContactRadius at the tap's contact threshold and stroke limit).
double sceneContactRadius(const SceneSpec& scene);

/// One sentence on what `reach` leaves out of `outline`, which `what` names ("/trials/0
/// (gear)"), or empty if every part of the contour is within reach.
std::string reachCaution(const Polygon& outline, const ContourReach& reach,
                         const std::string& what);

/// One caution per object the experiment follows (each trial's object once; the scene's object
/// when there are no trials) with features the fingertip cannot resolve.
std::vector<std::string> unresolvedFeatureCautions(const ExperimentSpec& e);

}  // namespace activetouch
