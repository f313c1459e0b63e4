#include "core/analysis/SeedRates.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "core/run/OutputFiles.h"
#include "core/stats/Intervals.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {
/// The rate kept for `label`, appended (empty) where the label is new.
Rate& rateOf(RatesByLabel& byLabel, const std::string& label) {
    auto it = std::find_if(byLabel.begin(), byLabel.end(),
                           [&](const auto& b) { return b.first == label; });
    if (it == byLabel.end()) it = byLabel.insert(byLabel.end(), {label, Rate{}});
    return it->second;
}

/// Where `label` stands in `labels`, appended where it is new.
std::size_t indexOf(std::vector<std::string>& labels, const std::string& label) {
    const auto it = std::find(labels.begin(), labels.end(), label);
    if (it != labels.end()) return static_cast<std::size_t>(it - labels.begin());
    labels.push_back(label);
    return labels.size() - 1;
}

}  // namespace

std::string csvField(const std::vector<std::string>& items) {
    std::string joined;
    for (const auto& item : items) joined += (joined.empty() ? "" : "; ") + item;
    std::string quoted = "\"";
    for (const char c : joined) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + '"';
}

int SeedOutcome::recognisedRaw() const {
    return static_cast<int>(std::count_if(namings.begin(), namings.end(),
                                          [](const PathNaming& n) { return n.raw == n.label; }));
}
int SeedOutcome::recognisedSmoothed() const {
    return static_cast<int>(std::count_if(
        namings.begin(), namings.end(), [](const PathNaming& n) { return n.smoothed == n.label; }));
}

int SeedOutcome::recognisedAnyPose() const {
    return static_cast<int>(std::count_if(
        namings.begin(), namings.end(), [](const PathNaming& n) { return n.anyPose == n.label; }));
}

std::vector<std::string> SeedOutcome::misnamed() const {
    std::vector<std::string> out;
    for (const PathNaming& n : namings)
        if (n.raw != n.label || n.smoothed != n.label)
            out.push_back(n.label + " trial " + std::to_string(n.trial) + ": " + n.raw +
                          " by the paper's rule, " + n.smoothed + " smoothed");
    return out;
}

std::string RecognitionConfusion::misnamedAnyPose() const {
    std::string out;
    for (std::size_t i = 0; i < anyPose.size(); ++i)
        for (std::size_t j = 0; j < anyPose[i].size(); ++j)
            if (i != j && anyPose[i][j] > 0)
                out += (out.empty() ? "" : ", ") + labels[i] + " as " + labels[j] + " " +
                       std::to_string(anyPose[i][j]);
    return out;
}

std::string RecognitionConfusion::misnamed(bool smoothedRule) const {
    const auto& counts = smoothedRule ? smoothed : raw;
    std::string out;
    for (std::size_t i = 0; i < counts.size(); ++i)
        for (std::size_t j = 0; j < counts[i].size(); ++j)
            if (i != j && counts[i][j] > 0)
                out += (out.empty() ? "" : ", ") + labels[i] + " as " + labels[j] + " " +
                       std::to_string(counts[i][j]);
    return out;
}

RecognitionConfusion recognitionConfusion(const std::vector<PathNaming>& namings,
                                          std::vector<std::string> labels) {
    RecognitionConfusion c;
    c.labels = std::move(labels);
    for (const PathNaming& n : namings) indexOf(c.labels, n.label);
    for (const PathNaming& n : namings) {
        indexOf(c.labels, n.raw);
        indexOf(c.labels, n.smoothed);
        if (!n.anyPose.empty()) indexOf(c.labels, n.anyPose);
    }
    const std::size_t size = c.labels.size();
    c.raw.assign(size, std::vector<int>(size, 0));
    c.smoothed = c.raw;
    c.anyPose = c.raw;
    for (const PathNaming& n : namings) {
        const std::size_t traced = indexOf(c.labels, n.label);
        ++c.raw[traced][indexOf(c.labels, n.raw)];
        ++c.smoothed[traced][indexOf(c.labels, n.smoothed)];
        if (!n.anyPose.empty()) ++c.anyPose[traced][indexOf(c.labels, n.anyPose)];
    }
    return c;
}

namespace {

PathNaming pathNaming(const TrialRun& t) {
    PathNaming n;
    n.label = t.label;
    n.trial = t.trial;
    n.raw = t.recognition.predicted;
    n.smoothed = t.recognition.predictedSmoothed;
    const PoseRecognition& p = t.poseRecognition;
    if (!p.valid) return n;
    n.anyPose = p.predicted;
    if (p.predicted != t.label) return n;
    if (p.best.symmetry != 0)
        n.turnError_deg = rotationErrorDeg(p.best.rotationDeg, t.rotationDeg, p.best.symmetry);
    n.placeError_mm = distance(p.best.position, t.objectCentre);
    return n;
}

}  // namespace

std::vector<PathNaming> pathNamings(const RunResult& run) {
    std::vector<PathNaming> namings;
    for (const TrialRun& t : run.trials)
        if (t.recognised) namings.push_back(pathNaming(t));
    return namings;
}

RecognitionConfusion recognitionConfusion(const RunResult& run) {
    std::vector<std::string> shapes;
    for (const auto& t : run.templates) shapes.push_back(t.shape);
    return recognitionConfusion(pathNamings(run), std::move(shapes));
}

SeedOutcome seedOutcome(const RunResult& run) {
    SeedOutcome o;
    o.seed = run.spec.scene.seed;
    o.runRobotTime_s = run.robotTime_s;
    o.angleError_deg = run.validation.angleError_deg;
    o.positionError_mm = run.validation.positionError_mm;
    o.validRange = run.validation.validRange;
    o.recognition = run.spec.recognition.enabled;
    o.runFailure = run.failure;
    o.sweeps = run.sweeps;
    int planned = 0;
    for (const TrialSpec& t : run.spec.trials) planned += t.repeats;
    int counted = 0;
    for (const TrialRun& t : run.trials) {
        if (t.result.end == TrialEnd::DeviceError) continue;  // the run failed, not the trial
        ++counted;
        const Tracing traced{1, t.result.coverage, t.result.meanContourDistance_mm};
        if (t.result.mode == FollowingMode::Passive) {
            ++o.passiveTrials;
            o.passiveLost += !t.result.completed();
            o.passiveCorners.add(t.result);
            if (!t.result.stoppedAtCorner())
                o.passiveShortfalls.push_back("passive " + t.label + " trial " +
                                              std::to_string(t.trial) + ": " + t.result.detail);
            Rate& label = rateOf(o.passiveByLabel, t.label);
            ++label.total;
            label.count += !t.result.completed();
            if (t.result.completed()) o.passiveTracing.add(traced);
            continue;
        }
        ++o.activeTrials;
        o.activeCorners.add(t.result);
        Rate& label = rateOf(o.activeByLabel, t.label);
        ++label.total;
        label.count += t.result.completed();
        if (!t.result.completed()) {
            o.failures.push_back(t.label + " trial " + std::to_string(t.trial) + ": " +
                                 t.result.detail);
            continue;
        }
        ++o.activeCompleted;
        if (t.recognised) o.namings.push_back(pathNaming(t));
        o.completedTaps += static_cast<int>(t.result.taps.size());
        o.completedRobotTime_s += t.result.robotTime_s;
        o.activeTracing.add(traced);
    }
    if (o.failed()) o.trialsNotRun = planned - counted;
    return o;
}

void CornerTally::add(const TrialResult& t) {
    rounded.convex += t.cornersRounded.convex;
    rounded.concave += t.cornersRounded.concave;
    if (t.completed()) return;
    switch (t.furthest.kind) {
        case PlaceKind::ConvexCorner:
            ++endedConvex;
            break;
        case PlaceKind::ConcaveCorner:
            ++endedConcave;
            break;
        case PlaceKind::AwayFromCorners:
            ++endedAway;
            break;
    }
}

void CornerTally::add(const CornerTally& o) {
    endedConvex += o.endedConvex;
    endedConcave += o.endedConcave;
    endedAway += o.endedAway;
    rounded.convex += o.rounded.convex;
    rounded.concave += o.rounded.concave;
}

void Tracing::add(const Tracing& other) {
    trials += other.trials;
    coverageSum += other.coverageSum;
    meanDistanceSum_mm += other.meanDistanceSum_mm;
}

namespace {
Rate sumOver(const std::vector<SeedOutcome>& seeds, Rate (*part)(const SeedOutcome&)) {
    stats::ClusteredProportion pooled;
    for (const auto& s : seeds) {
        const Rate p = part(s);
        pooled.add(p.count, p.total);
    }
    return Rate::pooled(pooled);
}

}  // namespace

Json rateJson(const Rate& r) {
    if (r.total == 0) return {{"count", 0}, {"total", 0}, {"rate", nullptr}, {"ci95", nullptr}};
    return {{"count", r.count},
            {"total", r.total},
            {"rate", r.fraction()},
            {"ci95", {r.low(), r.high()}},
            {"design_effect", r.designEffect}};
}

double Rate::low() const {
    return total > 0 ? stats::wilson(count, total, 0.95, designEffect).low : 0.0;
}
double Rate::high() const {
    return total > 0 ? stats::wilson(count, total, 0.95, designEffect).high : 1.0;
}

Rate passiveLostIn(const SeedOutcome& s) {
    return {s.passiveLost, s.passiveTrials};
}
Rate passiveLostAtCornerIn(const SeedOutcome& s) {
    return {s.passiveLostAtCorner(), s.passiveTrials};
}
Rate activeCompletedIn(const SeedOutcome& s) {
    return {s.activeCompleted, s.activeTrials};
}
Rate recognisedAnyPoseIn(const SeedOutcome& s) {
    return {s.recognisedAnyPose(), s.recognitionTrials()};
}

Rate recognisedRawIn(const SeedOutcome& s) {
    return {s.recognisedRaw(), s.recognitionTrials()};
}
Rate recognisedSmoothedIn(const SeedOutcome& s) {
    return {s.recognisedSmoothed(), s.recognitionTrials()};
}
Rate paperResultIn(const SeedOutcome& s) {
    if (!s.paperResultApplies()) return {0, 0};
    return {s.paperResult() ? 1 : 0, 1};
}
Rate paperResultSmoothedIn(const SeedOutcome& s) {
    if (!s.paperResultApplies()) return {0, 0};
    return {s.paperResultSmoothed() ? 1 : 0, 1};
}

Rate SeedRates::passiveLost() const {
    return sumOver(seeds, passiveLostIn);
}
Rate SeedRates::passiveLostAtCorner() const {
    return sumOver(seeds, passiveLostAtCornerIn);
}
Rate SeedRates::activeCompleted() const {
    return sumOver(seeds, activeCompletedIn);
}
Rate SeedRates::recognisedAnyPose() const {
    return sumOver(seeds, recognisedAnyPoseIn);
}

namespace {

/// The median of one error of every path named right at any pose that has it (-1 for none).
double medianOverNamings(const std::vector<SeedOutcome>& seeds, double PathNaming::*error) {
    std::vector<double> v;
    for (const auto& o : seeds)
        for (const PathNaming& n : o.namings)
            if (n.*error >= 0.0) v.push_back(n.*error);
    return stats::medianOr(v, -1.0);
}

}  // namespace

double SeedRates::medianTurnError_deg() const {
    return medianOverNamings(seeds, &PathNaming::turnError_deg);
}

double SeedRates::medianPlaceError_mm() const {
    return medianOverNamings(seeds, &PathNaming::placeError_mm);
}

Rate SeedRates::recognisedRaw() const {
    return sumOver(seeds, recognisedRawIn);
}
RatesByLabel SeedRates::recognisedRawByTrial() const {
    std::map<int, Rate> byTrial;
    for (const SeedOutcome& s : seeds)
        for (const PathNaming& n : s.namings) {
            Rate& r = byTrial[n.trial];
            ++r.total;
            r.count += n.raw == n.label;
        }
    RatesByLabel out;
    for (const auto& [trial, rate] : byTrial)
        out.emplace_back("trial " + std::to_string(trial), rate);
    return out;
}
Rate SeedRates::recognisedSmoothed() const {
    return sumOver(seeds, recognisedSmoothedIn);
}
Rate SeedRates::paperResult() const {
    return sumOver(seeds, paperResultIn);
}
Rate SeedRates::paperResultSmoothed() const {
    return sumOver(seeds, paperResultSmoothedIn);
}
ShortOfPaper SeedRates::shortOfPaper() const {
    ShortOfPaper s;
    for (const auto& o : seeds) {
        if (!o.paperResultApplies() || o.paperResult()) continue;
        ++s.runs;
        s.passiveNotLost += o.passiveLostAtCorner() < o.passiveTrials;
        s.activeLost += o.activeCompleted < o.activeTrials;
        s.misnamedRaw += o.recognisedRaw() < o.recognitionTrials();
    }
    return s;
}
RecognitionConfusion SeedRates::confusion() const {
    std::vector<PathNaming> namings;
    for (const auto& o : seeds) namings.insert(namings.end(), o.namings.begin(), o.namings.end());
    return recognitionConfusion(namings);
}
RatesByLabel SeedRates::byLabel(RatesByLabel SeedOutcome::*which) const {
    std::vector<std::string> labels;
    std::vector<stats::ClusteredProportion> pooled;
    for (const auto& s : seeds)
        for (const auto& [label, rate] : s.*which) {
            const std::size_t i = indexOf(labels, label);
            pooled.resize(labels.size());
            pooled[i].add(rate.count, rate.total);
        }
    RatesByLabel sums;
    for (std::size_t i = 0; i < labels.size(); ++i)
        sums.push_back({labels[i], Rate::pooled(pooled[i])});
    return sums;
}
RatesByLabel SeedRates::activeCompletedByLabel() const {
    return byLabel(&SeedOutcome::activeByLabel);
}
RatesByLabel SeedRates::passiveLostByLabel() const {
    return byLabel(&SeedOutcome::passiveByLabel);
}
std::vector<ValidRangeRate> SeedRates::activeCompletedByValidRange() const {
    std::map<std::pair<int, int>, std::pair<ValidRangeRate, stats::ClusteredProportion>> byRange;
    for (const auto& s : seeds) {
        if (s.activeTrials == 0) continue;
        auto& [r, pooled] = byRange[{s.validRange.first, s.validRange.last}];
        r.range = s.validRange;
        ++r.runs;
        pooled.add(s.activeCompleted, s.activeTrials);
    }
    std::vector<ValidRangeRate> list;
    for (auto& [positions, kept] : byRange) {
        kept.first.activeCompleted = Rate::pooled(kept.second);
        list.push_back(kept.first);
    }
    return list;
}

Tracing SeedRates::tracing(FollowingMode mode) const {
    Tracing sum;
    for (const auto& s : seeds)
        sum.add(mode == FollowingMode::Active ? s.activeTracing : s.passiveTracing);
    return sum;
}

CornerTally SeedRates::corners(FollowingMode mode) const {
    CornerTally sum;
    stats::ClusteredProportion convex, concave;
    for (const auto& s : seeds) {
        const CornerTally& own = mode == FollowingMode::Active ? s.activeCorners : s.passiveCorners;
        sum.add(own);
        convex.add(own.convexRounded().count, own.convexRounded().total);
        concave.add(own.concaveRounded().count, own.concaveRounded().total);
    }
    sum.convexDesignEffect = convex.designEffect();
    sum.concaveDesignEffect = concave.designEffect();
    return sum;
}

double SeedRates::tapsPerCompletedTrial() const {
    double taps = 0;
    for (const auto& s : seeds) taps += s.completedTaps;
    const int n = activeCompleted().count;
    return n > 0 ? taps / n : 0.0;
}
double SeedRates::robotTimePerCompletedTrial_s() const {
    double t = 0;
    for (const auto& s : seeds) t += s.completedRobotTime_s;
    const int n = activeCompleted().count;
    return n > 0 ? t / n : 0.0;
}
double SeedRates::robotTimePerRun_s() const {
    double t = 0;
    for (const auto& s : seeds) t += s.runRobotTime_s;
    return seeds.empty() ? 0.0 : t / static_cast<double>(seeds.size());
}

Rate SeedRates::runsFailed() const {
    Rate r;
    for (const SeedOutcome& s : seeds) {
        ++r.total;
        r.count += s.failed();
    }
    return r;
}

}  // namespace activetouch
