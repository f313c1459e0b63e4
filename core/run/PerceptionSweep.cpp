// The perception sweep: decisions from one tap to many at each belief threshold, on fresh
// repeated taps of every class (see Sweeps.h).
#include "core/run/PerceptionSweep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "core/classify/BeliefCalibration.h"
#include "core/classify/SequentialPerception.h"
#include "core/run/ExperimentRun.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {
namespace {

// The mean of per-decision values with a 95 % interval over the per-class means (decisions
// about one class share taps; the classes are the independent units).
SweepEstimate clusteredEstimate(const std::map<int, std::vector<double>>& byClass,
                                double least = 0.0,
                                double most = std::numeric_limits<double>::infinity()) {
    SweepEstimate e;
    std::vector<double> means;
    double sum = 0.0;
    std::size_t n = 0;
    for (const auto& [cls, values] : byClass) {
        if (values.empty()) continue;
        double m = 0.0;
        for (double v : values) m += v;
        sum += m;
        n += values.size();
        means.push_back(m / static_cast<double>(values.size()));
    }
    if (n == 0) return e;
    e.mean = sum / static_cast<double>(n);
    double spread = 0.0;
    if (means.size() > 1) {
        double mm = 0.0;
        for (double m : means) mm += m;
        mm /= static_cast<double>(means.size());
        for (double m : means) spread += (m - mm) * (m - mm);
        spread = std::sqrt(spread / static_cast<double>(means.size() - 1) /
                           static_cast<double>(means.size()));
    }
    // Clamped to the quantity's own range (an error is never negative, a fraction at most 1).
    e.low = std::max(least, e.mean - 1.96 * spread);
    e.high = std::min(most, e.mean + 1.96 * spread);
    return e;
}

/// Fresh repeated taps of every class, as the training protocol takes them.
std::vector<CollectedTap> perceptionSweepTaps(const RunResult& r, const RunOptions& options) {
    auto model = std::make_shared<const FingertipContactModel>(r.spec.scene.fingertip);
    SceneSpec scene = r.spec.scene;
    scene.seed = RandomStream::derived(r.spec.scene.seed, "sweep:perception").next() >> 1;
    const auto simulated = simulatedRigsOf(options).build(scene, model);
    Rig rig = simulated->rig();
    TrainingProtocolSettings protocol = r.spec.training;
    protocol.dataSets = std::max(2, r.spec.sweeps.tapsPerClass);
    protocol.trainingSets = {};
    return collectTrainingTaps(rig, simulated->object(), r.classes, protocol,
                               RandomStream::derived(scene.seed, "sweep:placement"),
                               [&](const CollectedTap&) { return !options.stopRequested(); });
}

using TapEvidence = std::map<const CollectedTap*, std::vector<double>>;

/// Each tap's evidence once: the run's calibrated belief where it was measured, else the
/// naive-Bayes log-likelihoods (whose posterior is near 1 after one tap). The belief's
/// calibration on these taps into `calibration`.
TapEvidence evidenceOf(const RunResult& r, const std::vector<CollectedTap>& taps,
                       PerceptionSweepCalibration& calibration) {
    const int C = r.classes.classCount();
    const bool useCalibrated = r.beliefCalibration.measured;
    TapEvidence evidence;
    std::vector<double> rawConfidence, calibratedConfidence;
    std::vector<bool> right;
    for (const auto& t : taps) {
        std::vector<double> ll(static_cast<std::size_t>(C));
        r.classifier.logLikelihoods(t.record.tap, ll.data());
        int top = 0;
        rawConfidence.push_back(calibratedTopBelief(ll.data(), C, BeliefScaling{}, &top));
        right.push_back(top == t.cls);
        if (useCalibrated) {
            calibratedConfidence.push_back(
                calibratedTopBelief(ll.data(), C, r.beliefCalibration.scaling, nullptr));
            std::vector<double> belief(ll.size());
            calibratedLogBelief(ll.data(), C, r.beliefCalibration.sequential, belief.data());
            ll = std::move(belief);
        }
        evidence[&t] = std::move(ll);
    }
    if (!taps.empty()) {
        calibration.measured = true;
        calibration.calibrated = useCalibrated;
        calibration.taps = static_cast<int>(taps.size());
        calibration.eceRaw = expectedCalibrationError(rawConfidence, right, 10);
        const auto& kept = useCalibrated ? calibratedConfidence : rawConfidence;
        calibration.eceCalibrated = expectedCalibrationError(kept, right, 10);
        calibration.eceIfCalibrated = expectedCalibrationErrorIfCalibrated(kept, 10);
    }
    return evidence;
}

using ByClass = std::map<int, std::vector<double>>;

/// The decisions at one belief threshold, per class: taps, robot time, errors and rightness.
struct ThresholdDecisions {
    ByClass taken, seconds, angle, position, correct;
};

/// Every decision at `threshold` (0: one tap, its most likely class): each starting tap of a
/// class begins one sequence through the class's repeats, in turn.
ThresholdDecisions decideAt(const RunResult& r,
                            const std::map<int, std::vector<const CollectedTap*>>& byClass,
                            const TapEvidence& evidence, double threshold,
                            PerceptionSweepRow& row) {
    ThresholdDecisions d;
    int planeRight = 0, airRight = 0;
    for (const auto& [cls, list] : byClass) {
        const Region truth = r.classes.regionOf(cls);
        for (std::size_t start = 0; start < list.size(); ++start) {
            SequentialBelief belief(r.classes);
            const CollectedTap* last = nullptr;
            double robot_s = 0.0;
            for (std::size_t k = 0;
                 k < list.size() && belief.taps() < r.spec.sweeps.maxTapsPerDecision; ++k) {
                last = list[(start + k) % list.size()];
                belief.update(evidence.at(last).data());
                robot_s += last->record.cycleTime_s;
                if (threshold == 0.0 || belief.decided(threshold)) break;
            }
            const int perceived = belief.best();
            d.taken[cls].push_back(belief.taps());
            d.seconds[cls].push_back(robot_s);
            d.position[cls].push_back(std::abs(r.classes.offsetOf(r.classes.positionOf(perceived)) -
                                               last->trueOffset_mm));
            d.correct[cls].push_back(perceived == cls ? 1.0 : 0.0);
            if (truth == Region::Edge) {
                d.angle[cls].push_back(angleDifferenceDeg(r.classes.orientationDegOf(perceived),
                                                          r.classes.orientationDegOf(cls)));
            } else if (truth == Region::Plane) {
                ++row.planeDecisions;
                planeRight += r.classes.regionOf(perceived) == Region::Plane;
            } else {
                ++row.airDecisions;
                airRight += r.classes.regionOf(perceived) == Region::Air;
            }
            ++row.decisions;
        }
    }
    row.planeRecognised = row.planeDecisions ? double(planeRight) / row.planeDecisions : 0.0;
    row.airRecognised = row.airDecisions ? double(airRight) / row.airDecisions : 0.0;
    return d;
}

/// How far the errors fall from the single tap's, decision by decision.
SweepEstimate fallFrom(const ByClass& first, const ByClass& now) {
    const double inf = std::numeric_limits<double>::infinity();
    ByClass d;
    for (const auto& [cls, values] : now) {
        const auto& before = first.at(cls);
        for (std::size_t i = 0; i < values.size(); ++i) d[cls].push_back(before[i] - values[i]);
    }
    return clusteredEstimate(d, -inf, inf);
}

}  // namespace

std::vector<PerceptionSweepRow> perceptionSweep(const RunResult& r, const RunOptions& options,
                                                PerceptionSweepCalibration& calibration,
                                                PerceptionSweepRow& singleTap) {
    const auto taps = perceptionSweepTaps(r, options);
    std::map<int, std::vector<const CollectedTap*>> byClass;
    for (const auto& t : taps) byClass[t.cls].push_back(&t);
    const TapEvidence evidence = evidenceOf(r, taps, calibration);
    std::vector<PerceptionSweepRow> rows;
    // The single tap's errors, decision by decision, to pair each threshold's with.
    ByClass firstAngle, firstPosition;
    // First the paper's operating point on the same taps and axes: one tap, its most likely
    // class (threshold 0); then each threshold.
    std::vector<double> thresholds{0.0};
    const auto& more = r.spec.sweeps.beliefThresholds;
    thresholds.insert(thresholds.end(), more.begin(), more.end());
    for (double threshold : thresholds) {
        PerceptionSweepRow row;
        row.threshold = threshold;
        const ThresholdDecisions d = decideAt(r, byClass, evidence, threshold, row);
        if (row.decisions == 0) break;
        row.taps = clusteredEstimate(d.taken, 1.0);
        row.robotTime_s = clusteredEstimate(d.seconds);
        row.angle_deg = clusteredEstimate(d.angle);
        row.position_mm = clusteredEstimate(d.position);
        row.correct = clusteredEstimate(d.correct, 0.0, 1.0);
        row.meanTaps = row.taps.mean;
        row.meanRobotTime_s = row.robotTime_s.mean;
        row.angleError_deg = row.angle_deg.mean;
        row.positionError_mm = row.position_mm.mean;
        row.correctFraction = row.correct.mean;
        if (threshold == 0.0) {
            firstAngle = d.angle;
            firstPosition = d.position;
        }
        row.angleFall_deg = fallFrom(firstAngle, d.angle);
        row.positionFall_mm = fallFrom(firstPosition, d.position);
        if (threshold == 0.0)
            singleTap = row;
        else
            rows.push_back(row);
    }
    return rows;
}

}  // namespace activetouch
