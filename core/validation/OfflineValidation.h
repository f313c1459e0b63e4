#pragma once
// Offline validation (paper Figures 5, 6; docs/design.md §3): classify every test tap and measure,
// per (orientation, position), the mean angle error (deg) and position error (mm); average over
// orientations with +-1 std; derive the valid range for repositioning from those errors.
#include <string>
#include <vector>

#include "core/classify/HistogramClassifier.h"
#include "core/classify/Percept.h"
#include "core/tap/ClassSet.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

struct ClassError {
    int orientationIndex = 0;
    int position = 1;
    Region region = Region::Edge;
    int taps = 0;
    double angleError_deg = 0.0;    ///< mean over test taps
    double positionError_mm = 0.0;  ///< mean |perceived - true| over test taps
    double correctFraction = 0.0;   ///< exact class hits
    /// Continuous percept (when validated): mean angle error of the taps it gave an angle, deg.
    double continuousAngleError_deg = 0.0;
    int continuousTaps = 0;
};

/// The valid range rule: over every window of `width` consecutive positions, the sum of the
/// orientation-averaged errors, each normalised by its largest value over positions
/// (angle / max angle + position / max position); the lowest sum wins, ties go to the window
/// whose centre is nearest the edge, then to the lower window.
struct ValidRange {
    int first = 1, last = 1;  ///< class positions, inclusive
    double score = 0.0;
    /// "8-11": the positions (millimetres at the paper's 1 mm steps).
    std::string span() const { return std::to_string(first) + "-" + std::to_string(last); }
    /// "valid range 8-11 mm", as runs print it.
    std::string text() const { return "valid range " + span() + " mm"; }
};
ValidRange deriveValidRange(const std::vector<double>& angleByPosition,
                            const std::vector<double>& positionByPosition, int width);

struct ValidationResult {
    std::vector<ClassError> byClass;  ///< orientation-major, like class indices
    std::vector<double> angleMean, angleStd, positionMean,
        positionStd;              ///< per position, over orientations
    double angleError_deg = 0.0;  ///< mean over all test taps
    double positionError_mm = 0.0;
    double correctFraction = 0.0;
    ValidRange validRange;
    std::vector<int> confusion;     ///< classCount x classCount, true-major
    std::vector<Percept> percepts;  ///< per test tap, in the order given
    /// The continuous percept (core/classify/Percept.h), validated when asked: the median angle
    /// error of the edge classes' test taps at positions inside the valid range, and over every
    /// edge class's test taps; -1 when not validated or no tap gave an angle.
    bool continuousValidated = false;
    double continuousMedianAngleErrorInRange_deg = -1.0;
    double continuousMedianAngleError_deg = -1.0;
};

/// `continuousTemperature`: also validate the continuous percept at this temperature (0: the
/// tap's samples per taxel); below 0, do not.
ValidationResult validateOffline(const HistogramClassifier& classifier, const ClassSet& classes,
                                 const std::vector<const CollectedTap*>& testTaps,
                                 int validRangeWidth, double continuousTemperature = -1.0);

}  // namespace activetouch
