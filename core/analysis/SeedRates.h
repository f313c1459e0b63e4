#pragma once
// Outcome rates over many seeds (docs/design.md §3: one seed is a whole run, its own data sets,
// training, valid range and trials). A single training draw can make a setting look much better
// or worse than it is, so the paper's claims are reported as rates with their 95 % intervals.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/io/OutputFile.h"
#include "core/run/ExperimentRun.h"
#include "core/run/SeedPool.h"
#include "core/stats/Intervals.h"

namespace activetouch {

/// A count out of a total with its Wilson score 95 % interval. Pooled over seeds, each seed is
/// one independent unit (its trials share its training run): the interval is on the effective
/// total its design effect gives (stats::ClusteredProportion).
struct Rate {
    int count = 0, total = 0;
    double designEffect = 1.0;
    double fraction() const { return total > 0 ? double(count) / total : 0.0; }
    double low() const;
    double high() const;
    /// The counts pooled over clusters (one a seed), with their design effect.
    static Rate pooled(const stats::ClusteredProportion& p) {
        return {p.count(), p.total(), p.designEffect()};
    }
};

/// `items` joined by "; " as one quoted CSV field (quotes inside doubled).
std::string csvField(const std::vector<std::string>& items);

/// {"count", "total", "rate", "ci95": [low, high]}; rate and ci95 null where the total is 0.
Json rateJson(const Rate& r);

/// Active trials completed per trial label (a shape, or the label a trial gives), in the order
/// the labels first appear.
using RatesByLabel = std::vector<std::pair<std::string, Rate>>;

/// A completed active path and the shape each recognition rule named it.
struct PathNaming {
    std::string label;  ///< the trial's label, the shape it traced
    int trial = 0;
    std::string raw, smoothed;  ///< named by the paper's rule and by the smoothed histograms
    std::string anyPose;        ///< named at any pose (core/recognition/PoseRecognition.h)
    /// Named right at any pose: how far the recovered turn (modulo the shape's symmetry; -1 for
    /// a shape without one) and place were from the truth.
    double turnError_deg = -1.0, placeError_mm = -1.0;
};

/// How closely completed trials traced the contour: how many, and the sums of their coverage
/// and mean distance to the contour (a run's, or over runs).
struct Tracing {
    int trials = 0;
    double coverageSum = 0.0, meanDistanceSum_mm = 0.0;
    double coverage() const { return trials > 0 ? coverageSum / trials : 0.0; }
    double meanDistance_mm() const { return trials > 0 ? meanDistanceSum_mm / trials : 0.0; }
    void add(const Tracing& other);
};

/// Where the trials of one mode that did not complete got furthest (near which kind of corner,
/// or away from corners), and the corners its trials got round: of the corners a trial met, the
/// ones it went past and the one it did not get beyond.
struct CornerTally {
    int endedConvex = 0, endedConcave = 0, endedAway = 0;  ///< trials not completed
    CornerCount rounded;
    /// Over seeds: the design effects of the convex and concave rates (SeedRates::corners).
    double convexDesignEffect = 1.0, concaveDesignEffect = 1.0;
    void add(const TrialResult& trial);
    void add(const CornerTally& other);
    int notCompleted() const { return endedConvex + endedConcave + endedAway; }
    Rate convexRounded() const {
        return {rounded.convex, rounded.convex + endedConvex, convexDesignEffect};
    }
    Rate concaveRounded() const {
        return {rounded.concave, rounded.concave + endedConcave, concaveDesignEffect};
    }
};

/// One whole run's outcome.
struct SeedOutcome {
    std::uint64_t seed = 0;
    int passiveTrials = 0, passiveLost = 0;
    int activeTrials = 0, activeCompleted = 0;
    bool recognition = false;           ///< the experiment recognises shapes from the paths
    int completedTaps = 0;              ///< taps of the completed active trials
    double completedRobotTime_s = 0.0;  ///< their robot time
    double runRobotTime_s = 0.0;        ///< the whole run, training included
    double angleError_deg = 0.0, positionError_mm = 0.0;  ///< offline validation
    ValidRange validRange;                                ///< the positions the validation picked
    /// A device or rig error that stopped the run (a stage asked past its travel, a stream that
    /// dropped): the run failed, its trial in flight and the ones after it were not run and count
    /// in no trial rate.
    std::string runFailure;
    int trialsNotRun = 0;
    bool failed() const { return !runFailure.empty(); }
    std::vector<std::string> failures;  ///< "cross trial 2: lost: ..." for each active trial lost
    /// "passive rectangle trial 2: completed ..." for each passive trial not lost at a corner.
    std::vector<std::string> passiveShortfalls;
    std::vector<PathNaming> namings;  ///< each recognised completed active path
    RatesByLabel activeByLabel;       ///< active trials completed, per trial label
    RatesByLabel passiveByLabel;      ///< passive trials lost, per trial label
    /// The completed trials of each mode: a passive trial that gets round does so without ever
    /// correcting its offset from the edge, and these say how closely it traced the contour.
    Tracing activeTracing, passiveTracing;
    CornerTally activeCorners, passiveCorners;
    /// The run's accuracy-versus-time sweeps, if the experiment has them (SweepRates.h sets them
    /// over seeds).
    SweepResults sweeps;
    /// Passive trials lost where they got no further than near a corner.
    int passiveLostAtCorner() const {
        return passiveCorners.endedConvex + passiveCorners.endedConcave;
    }

    /// Completed active paths recognition looked at, and of those the ones each rule named rightly.
    int recognitionTrials() const { return static_cast<int>(namings.size()); }
    int recognisedRaw() const;
    int recognisedSmoothed() const;
    int recognisedAnyPose() const;
    /// "rectangle trial 1: c by the paper's rule, rectangle smoothed" for each path either rule
    /// misnamed.
    std::vector<std::string> misnamed() const;

    /// Whether the run has the paper's parts: passive and active trials, and recognition.
    bool paperResultApplies() const {
        return !failed() && passiveTrials > 0 && activeTrials > 0 && recognition;
    }
    /// The paper's result whole in this run: every passive trial lost, every active trial
    /// completed and every active path recognised by the paper's rule.
    bool paperResult() const { return paperFollowing() && recognisedRaw() == recognitionTrials(); }
    /// The same with the smoothed histograms deciding recognition.
    bool paperResultSmoothed() const {
        return paperFollowing() && recognisedSmoothed() == recognitionTrials();
    }
    /// The paper's parts, every passive trial lost at a corner and every active trial completed.
    bool paperFollowing() const {
        return paperResultApplies() && passiveLostAtCorner() == passiveTrials &&
               activeCompleted == activeTrials;
    }
};

/// Of the runs with the paper's parts, how many fall short of its result in each part (a run may
/// fall short in several).
struct ShortOfPaper {
    int runs = 0;            ///< runs without the paper's result whole
    int passiveNotLost = 0;  ///< a passive trial completed, or was lost away from corners
    int activeLost = 0;      ///< an active trial did not complete
    int misnamedRaw = 0;     ///< a completed active path misnamed by the paper's rule
};

SeedOutcome seedOutcome(const RunResult& run);

/// Recognition over trials: how often each traced shape was named as each shape, by both rules.
/// Rows are the traced shapes, columns the names, over one list of labels.
struct RecognitionConfusion {
    std::vector<std::string> labels;
    std::vector<std::vector<int>> raw, smoothed, anyPose;  ///< [traced][named]
    /// "rectangle as c 3, c as rectangle 1" for the paths one rule misnamed; empty if none.
    std::string misnamed(bool smoothedRule) const;
    std::string misnamedAnyPose() const;
};

/// The confusion of `namings` over `labels` (kept in their order), then the traced shapes in the
/// order they first appear, then any other name a rule gave.
RecognitionConfusion recognitionConfusion(const std::vector<PathNaming>& namings,
                                          std::vector<std::string> labels = {});

/// Each trial of `run` that recognition looked at, with the shape each rule named it.
std::vector<PathNaming> pathNamings(const RunResult& run);

/// One run's confusion over its recognised trials, labelled in the order of its templates (the
/// shapes of the experiment's library), then any other shape traced or named.
RecognitionConfusion recognitionConfusion(const RunResult& run);

/// One run's part in each rate: its count and its total, which SeedRates sums over runs.
Rate passiveLostIn(const SeedOutcome& run);
Rate passiveLostAtCornerIn(const SeedOutcome& run);  ///< of its passive trials
Rate activeCompletedIn(const SeedOutcome& run);
Rate recognisedRawIn(const SeedOutcome& run);       ///< of its recognised completed active paths
Rate recognisedSmoothedIn(const SeedOutcome& run);  ///< of its recognised completed active paths
Rate recognisedAnyPoseIn(const SeedOutcome& run);   ///< of its recognised completed active paths
Rate paperResultIn(const SeedOutcome& run);  ///< 1 of 1 or 0 of 1; 0 of 0 where it does not apply
Rate paperResultSmoothedIn(const SeedOutcome& run);  ///< as paperResultIn, smoothed recognition

/// The runs whose validation picked one valid range, and their active trials completed.
struct ValidRangeRate {
    ValidRange range;
    int runs = 0;
    Rate activeCompleted;
};

struct SeedRates {
    std::vector<SeedOutcome> seeds;
    Rate runsFailed() const;  ///< of runs: stopped by a device or rig error
    Rate passiveLost() const;
    Rate passiveLostAtCorner() const;  ///< of passive trials
    Rate activeCompleted() const;
    Rate recognisedRaw() const;  ///< of completed active paths
    /// The same per trial number ("trial 1", "trial 2", ...): a rule handed the pose of one
    /// trial would name that trial's paths better than the others.
    RatesByLabel recognisedRawByTrial() const;
    Rate recognisedSmoothed() const;  ///< of completed active paths
    Rate recognisedAnyPose() const;   ///< of completed active paths
    /// Over the paths named right at any pose: the median error of the recovered turn (shapes
    /// with one) and place; -1 where there is none.
    double medianTurnError_deg() const;
    double medianPlaceError_mm() const;
    Rate paperResult() const;          ///< of runs: SeedOutcome::paperResult
    Rate paperResultSmoothed() const;  ///< of runs: SeedOutcome::paperResultSmoothed
    ShortOfPaper shortOfPaper() const;
    RecognitionConfusion confusion() const;
    RatesByLabel activeCompletedByLabel() const;
    RatesByLabel passiveLostByLabel() const;
    /// Active trials completed over the runs whose validation picked each valid range, lowest
    /// positions first.
    std::vector<ValidRangeRate> activeCompletedByValidRange() const;
    /// A per-label rate of every seed, summed per label in the order the labels first came.
    RatesByLabel byLabel(RatesByLabel SeedOutcome::*which) const;
    Tracing tracing(FollowingMode mode) const;      ///< of the completed trials in `mode`
    CornerTally corners(FollowingMode mode) const;  ///< of the trials in `mode`
    double tapsPerCompletedTrial() const;
    double robotTimePerCompletedTrial_s() const;
    double robotTimePerRun_s() const;
};

/// Runs `spec` once per seed from `first` to `last` (no per-run artefacts), `jobs` seeds at once
/// (forEachSeed: the results are the same for any number). With `outDir`, each seed's row is
/// appended to <outDir>/rates.csv as it finishes, in seed order, and <outDir>/rates.json is
/// written at the end. `seedDone` sees each outcome in seed order; returning false stops after
/// that seed. `before` are the outcomes of seeds before `first` that an earlier run of the same
/// block finished (a run resumed from its journal, SeedJournal.h): they lead the rates and the
/// table as if run here.
SeedRates runSeeds(const SimulatedRigs& rigs, const ExperimentSpec& spec, std::uint64_t first,
                   std::uint64_t last, const std::string& outDir,
                   const std::function<bool(const SeedOutcome&)>& seedDone = {},
                   int jobs = defaultSeedJobs(), const std::vector<SeedOutcome>& before = {});

/// The rates, and with them the sweeps over seeds where the runs measured any.
Json seedRatesJson(const SeedRates& rates);
/// Writes <outDir>/rates.json, and the sweep tables over seeds (SweepRates.h) where there are.
void writeSeedRatesFiles(const SeedRates& rates, const std::string& outDir);

/// Opens <outDir>/rates.csv with its header (removing a rates.json beside it), and appends one
/// seed's row: what runSeeds writes, and a merge of shards writes again.
void startRatesTable(std::optional<OutputFile>& file, const std::string& outDir);
void appendRatesRow(OutputFile& file, const SeedOutcome& outcome);

/// The rates as lines of text, one per rate ("<what>  count / total  p %  (95 % interval lo-hi
/// %)", or that there are none; with more than one trial label, active completion per label under
/// the overall rate; under each recognition rate, which shapes it misnamed as which), in which
/// parts the runs short of the paper's result fall short, then what a
/// completed active trial and a whole run cost in taps and robot time, and how closely the
/// completed trials of each mode traced the contour.
std::vector<std::string> describeRates(const SeedRates& rates);

/// One entry of the rates report: a rate (count of total, with its interval) or a note, and how
/// far it is indented under the entry it belongs to.
struct ReportRow {
    std::string what;
    std::optional<Rate> rate;  ///< none: a note
    int indent = 0;
};
/// The rates report as entries, in the order describeRates writes them (the window's table).
std::vector<ReportRow> rateReport(const SeedRates& rates);

}  // namespace activetouch
