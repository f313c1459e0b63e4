#include "core/analysis/SweepRates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

#include "core/stats/Distributions.h"
#include "core/stats/Intervals.h"
#include "core/stats/Resampling.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr int kResamples = 2000;

std::pair<double, double> asPair(const stats::Interval& i) {
    return {i.low, i.high};
}

struct SettingSums {
    double time = 0, completed = 0;
};

double ratio(const SettingSums& s) {
    return s.completed > 0 ? s.time / s.completed : kInf;
}

}  // namespace

SweepEstimate overSeeds(const std::vector<double>& perSeed, double least, double most) {
    const stats::MeanInterval m = stats::studentMean(perSeed, least, most);
    return {m.mean, m.low, m.high};
}

PaperVerdict paperVerdict(const FollowingOverSeeds& f) {
    const SweepEstimate &c = f.completionDifference_points, &r = f.timeRatio;
    const bool informative = f.pairedSeeds >= kMinVerdictSeeds && std::isfinite(r.low) &&
                             std::isfinite(r.high) && r.high > r.low && std::isfinite(c.low) &&
                             std::isfinite(c.high) && c.high > c.low;
    if (!informative) return PaperVerdict::NotEnoughSeeds;
    return r.high < 1.0 && c.low > -kCompletionMargin_points ? PaperVerdict::Beats
                                                             : PaperVerdict::DoesNotBeat;
}

namespace {

using Runs = std::vector<const SweepResults*>;

/// (a) for one row of the perception sweep: each figure the mean of the seeds' means; an angle
/// error only where the seed had edge decisions, a plane (air) share only where it had plane
/// (air) decisions.
template <typename RowOf>
PerceptionOverSeeds perceptionOverSeeds(const Runs& runs, RowOf rowOf, double threshold) {
    PerceptionOverSeeds p;
    p.threshold = threshold;
    std::vector<double> taps, time, angle, position, correct, angleFall, positionFall, plane, air;
    for (const SweepResults* r : runs) {
        const PerceptionSweepRow* row = rowOf(*r);
        if (!row || row->decisions == 0) continue;
        ++p.seeds;
        taps.push_back(row->meanTaps);
        time.push_back(row->meanRobotTime_s);
        angle.push_back(row->angleError_deg);
        position.push_back(row->positionError_mm);
        correct.push_back(row->correctFraction);
        angleFall.push_back(row->angleFall_deg.mean);
        positionFall.push_back(row->positionFall_mm.mean);
        if (row->planeDecisions > 0) plane.push_back(row->planeRecognised);
        if (row->airDecisions > 0) air.push_back(row->airRecognised);
    }
    p.taps = overSeeds(taps, 1.0);
    p.robotTime_s = overSeeds(time, 0.0);
    p.angle_deg = overSeeds(angle, 0.0);
    p.position_mm = overSeeds(position, 0.0);
    p.correct = overSeeds(correct, 0.0, 1.0);
    p.angleFall_deg = overSeeds(angleFall);
    p.positionFall_mm = overSeeds(positionFall);
    p.planeRecognised = overSeeds(plane, 0.0, 1.0);
    p.airRecognised = overSeeds(air, 0.0, 1.0);
    return p;
}

void addPerception(SweepRates& out, const Runs& runs) {
    const SweepResults& first = *runs.front();
    for (std::size_t i = 0; i < first.perception.size(); ++i)
        out.perception.push_back(perceptionOverSeeds(
            runs,
            [i](const SweepResults& r) {
                return i < r.perception.size() ? &r.perception[i] : nullptr;
            },
            first.perception[i].threshold));
    if (!first.perception.empty())
        out.perceptionSingleTap = perceptionOverSeeds(
            runs,
            [](const SweepResults& r) {
                return r.perception.empty() ? nullptr : &r.perceptionSingleTap;
            },
            0.0);
    std::vector<double> raw, calibrated, ideal;
    for (const SweepResults* r : runs) {
        const PerceptionSweepCalibration& c = r->perceptionCalibration;
        if (!c.measured) continue;
        ++out.calibrationSeeds;
        out.calibrationWithin005 += c.eceCalibrated <= 0.05;
        raw.push_back(c.eceRaw);
        calibrated.push_back(c.eceCalibrated);
        ideal.push_back(c.eceIfCalibrated);
    }
    out.eceRaw = overSeeds(raw, 0.0, 1.0);
    out.eceCalibrated = overSeeds(calibrated, 0.0, 1.0);
    out.eceIfCalibrated = overSeeds(ideal, 0.0, 1.0);
}

/// Each setting's robot time and completions in each run, [setting][run], and the resampled
/// seeds every setting shares so that the pairs stay paired.
struct FollowingSums {
    std::vector<std::vector<SettingSums>> sums;
    std::vector<std::vector<std::size_t>> draws;
    SettingSums resampled(std::size_t setting, const std::vector<std::size_t>& d) const {
        SettingSums t;
        for (std::size_t k : d) {
            t.time += sums[setting][k].time;
            t.completed += sums[setting][k].completed;
        }
        return t;
    }
    SettingSums total(std::size_t setting) const {
        SettingSums t;
        for (const SettingSums& s : sums[setting]) t.time += s.time, t.completed += s.completed;
        return t;
    }
};

/// (b) per setting over seeds; fills `sums` with each run's sums.
FollowingOverSeeds followingOverSeeds(const Runs& runs, std::size_t i, FollowingSums& sums) {
    const FollowingSweepRow& head = runs.front()->following[i];
    FollowingOverSeeds f;
    f.mode = head.mode;
    f.followStep_mm = head.followStep_mm;
    f.repositionStep_mm = head.repositionStep_mm;
    f.beliefThreshold = head.beliefThreshold;
    f.paperSetting = head.paperSetting;
    std::vector<double> distance, time, taps;
    stats::ClusteredProportion completed;
    for (const SweepResults* r : runs) {
        SettingSums s;
        if (i < r->following.size() && r->following[i].trials > 0) {
            const FollowingSweepRow& row = r->following[i];
            ++f.seeds;
            completed.add(row.completed, row.trials);
            distance.push_back(row.meanContourDistance_mm);
            time.push_back(row.meanRobotTime_s);
            taps.push_back(row.meanTaps);
            s = {row.meanRobotTime_s * row.trials, double(row.completed)};
        }
        sums.sums[i].push_back(s);
    }
    f.completed = Rate::pooled(completed);
    f.contourDistance_mm = overSeeds(distance, 0.0);
    f.robotTimePerTrial_s = overSeeds(time, 0.0);
    f.tapsPerTrial = overSeeds(taps, 0.0);
    f.robotTimePerCompletion_s.mean = ratio(sums.total(i));
    return f;
}

/// Every seed gave the same completion difference (each setting completed all its trials, say):
/// the seeds show no spread, which is no evidence of none. The interval is then the score
/// interval of a paired difference with no discordant pairs beyond those the difference needs:
/// +/- z^2 / (N + z^2) over the N paired trials (Tango's for a difference of 0), so that it
/// narrows only as trials accumulate.
void widenUniformDifference(SweepEstimate& c, const Runs& runs, std::size_t i, std::size_t paper) {
    int pairedTrials = 0;
    for (const SweepResults* r : runs) {
        const auto& rows = r->following;
        if (std::max(i, paper) < rows.size() && rows[i].trials > 0 && rows[paper].trials > 0)
            pairedTrials += std::min(rows[i].trials, rows[paper].trials);
    }
    const double z = stats::normalTwoSided(), z2 = z * z;
    const double half = 100.0 * z2 / (pairedTrials + z2);
    c.low = std::max(-100.0, c.mean - half);
    c.high = std::min(100.0, c.mean + half);
}

/// (b) against the paper's setting of the same mode, seed by seed.
void pairWithPaper(FollowingOverSeeds& f, const Runs& runs, std::size_t i, std::size_t paper,
                   const FollowingSums& sums) {
    f.paired = true;
    std::vector<double> completion, distance;
    for (const SweepResults* r : runs) {
        const auto& rows = r->following;
        if (std::max(i, paper) >= rows.size() || rows[i].trials == 0 || rows[paper].trials == 0)
            continue;
        completion.push_back(100.0 * (double(rows[i].completed) / rows[i].trials -
                                      double(rows[paper].completed) / rows[paper].trials));
        distance.push_back(rows[i].meanContourDistance_mm - rows[paper].meanContourDistance_mm);
    }
    f.completionDifference_points = overSeeds(completion);
    if (completion.size() > 1 &&
        f.completionDifference_points.high == f.completionDifference_points.low)
        widenUniformDifference(f.completionDifference_points, runs, i, paper);
    f.distanceDifference_mm = overSeeds(distance);
    std::vector<double> ratios;
    for (const auto& d : sums.draws)
        ratios.push_back(ratio(sums.resampled(i, d)) / ratio(sums.resampled(paper, d)));
    f.timeRatio.mean = ratio(sums.total(i)) / ratio(sums.total(paper));
    std::tie(f.timeRatio.low, f.timeRatio.high) = asPair(stats::percentileInterval(ratios));
    f.pairedSeeds = static_cast<int>(completion.size());
    f.verdict = paperVerdict(f);
    f.beatsPaper = f.verdict == PaperVerdict::Beats;
}

/// The front: no other setting at most as slow per completion, at least as complete and at most
/// as far from the contour, and better in one of them.
void markParetoFront(std::vector<FollowingOverSeeds>& following) {
    for (FollowingOverSeeds& f : following) {
        const double t = f.robotTimePerCompletion_s.mean, c = f.completed.fraction(),
                     d = f.contourDistance_mm.mean;
        f.onParetoFront = f.completed.count > 0;
        for (const FollowingOverSeeds& g : following) {
            const double tg = g.robotTimePerCompletion_s.mean, cg = g.completed.fraction(),
                         dg = g.contourDistance_mm.mean;
            if (tg <= t && cg >= c && dg <= d && (tg < t || cg > c || dg < d))
                f.onParetoFront = false;
        }
    }
}

void addFollowing(SweepRates& out, const Runs& runs) {
    const std::size_t settings = runs.front()->following.size(), n = runs.size();
    FollowingSums sums;
    sums.sums.resize(settings);
    for (std::size_t i = 0; i < settings; ++i)
        out.following.push_back(followingOverSeeds(runs, i, sums));
    sums.draws.assign(kResamples, std::vector<std::size_t>(n));
    stats::ResamplingGenerator generator{0x5eed5eedULL};
    for (auto& d : sums.draws)
        for (auto& k : d) k = generator.below(n);
    for (std::size_t i = 0; i < settings; ++i) {
        std::vector<double> values;
        for (const auto& d : sums.draws) values.push_back(ratio(sums.resampled(i, d)));
        std::tie(out.following[i].robotTimePerCompletion_s.low,
                 out.following[i].robotTimePerCompletion_s.high) =
            asPair(stats::percentileInterval(values));
    }
    for (std::size_t i = 0; i < settings; ++i) {
        std::size_t paper = settings;
        for (std::size_t j = 0; j < settings; ++j)
            if (out.following[j].paperSetting && out.following[j].mode == out.following[i].mode)
                paper = j;
        if (paper != settings && paper != i) pairWithPaper(out.following[i], runs, i, paper, sums);
    }
    markParetoFront(out.following);
}

/// (d): each seed's choice against that seed's best, and against the best over seeds.
void addBandit(SweepRates& out, const Runs& runs) {
    BanditOverSeeds& b = out.bandit;
    int pooledBest = -1;
    double pooledBestReward = -kInf;
    std::vector<double> pooledReward(out.following.size(), -kInf);
    for (const SweepResults* r : runs)
        if (r->bandit.ran) b.completionWorth_s = r->bandit.completionWorth_s;
    for (std::size_t i = 0; i < out.following.size() && b.completionWorth_s > 0; ++i) {
        const FollowingOverSeeds& f = out.following[i];
        if (f.mode != FollowingMode::Active || f.completed.total == 0) continue;
        pooledReward[i] = f.completed.fraction() - f.robotTimePerTrial_s.mean / b.completionWorth_s;
        if (pooledReward[i] > pooledBestReward)
            pooledBestReward = pooledReward[i], pooledBest = int(i);
    }
    b.pooledBest = pooledBest;
    std::vector<double> regret, pooled;
    std::map<int, int> chosen;
    for (const SweepResults* r : runs) {
        const BanditResult& x = r->bandit;
        if (!x.ran || x.chosen < 0 || x.sweepBest < 0) continue;
        ++b.seeds;
        b.choseBest += x.chosen == x.sweepBest;
        regret.push_back(x.bestSweepReward - x.chosenSweepReward);
        const int row = x.arms[std::size_t(x.chosen)].sweepRow;
        ++chosen[row];
        if (row >= 0 && std::size_t(row) < pooledReward.size())
            pooled.push_back(pooledBestReward - pooledReward[std::size_t(row)]);
        b.robotTime_s += x.robotTime_s;
        b.sweepRobotTime_s += x.sweepRobotTime_s;
    }
    b.regret = overSeeds(regret, 0.0);
    b.pooledRegret = overSeeds(pooled, 0.0);
    for (const auto& [row, count] : chosen) b.choices.push_back({row, count});
    std::stable_sort(b.choices.begin(), b.choices.end(),
                     [](const auto& a, const auto& c) { return a.second > c.second; });
}

/// (e): one fault's rates, and its fall below the same seed's fault-free run.
template <typename RowOf>
RobustnessOverSeeds robustnessOverSeeds(const Runs& runs, RowOf rowOf, const std::string& fault) {
    RobustnessOverSeeds f;
    f.fault = fault;
    std::vector<double> completion, recognition, angle;
    stats::ClusteredProportion completed, recognisedRaw, recognisedAnyPose;
    for (const SweepResults* r : runs) {
        const RobustnessRow* row = rowOf(*r);
        if (!row) continue;
        ++f.seeds;
        if (!row->failure.empty()) {
            ++f.failedRuns;
            continue;
        }
        const RobustnessRow& base = r->robustnessBase;
        completed.add(row->activeCompleted, row->activeTrials);
        recognisedRaw.add(row->recognisedRaw, row->recognitionTrials);
        recognisedAnyPose.add(row->recognisedAnyPose, row->recognitionTrials);
        angle.push_back(row->angleError_deg);
        // Falls over the trials run: completion, and paths completed and named rightly.
        if (row->activeTrials > 0 && base.activeTrials > 0 && base.failure.empty()) {
            completion.push_back(100.0 * (double(base.activeCompleted) / base.activeTrials -
                                          double(row->activeCompleted) / row->activeTrials));
            recognition.push_back(100.0 * (double(base.recognisedRaw) / base.activeTrials -
                                           double(row->recognisedRaw) / row->activeTrials));
        }
    }
    f.completed = Rate::pooled(completed);
    f.recognisedRaw = Rate::pooled(recognisedRaw);
    f.recognisedAnyPose = Rate::pooled(recognisedAnyPose);
    f.completionFall_points = overSeeds(completion);
    f.recognitionFall_points = overSeeds(recognition);
    f.angleError_deg = overSeeds(angle, 0.0);
    return f;
}

void addRobustness(SweepRates& out, const Runs& runs) {
    const SweepResults& first = *runs.front();
    if (first.robustness.empty()) return;
    out.robustnessBase = robustnessOverSeeds(
        runs,
        [](const SweepResults& r) { return r.robustness.empty() ? nullptr : &r.robustnessBase; },
        "none");
    for (std::size_t i = 0; i < first.robustness.size(); ++i)
        out.robustness.push_back(robustnessOverSeeds(
            runs,
            [i](const SweepResults& r) {
                return i < r.robustness.size() ? &r.robustness[i] : nullptr;
            },
            first.robustness[i].fault));
}

void addCompute(SweepRates& out, const Runs& runs) {
    const SweepResults& first = *runs.front();
    for (std::size_t i = 0; i < first.compute.size(); ++i) {
        ComputeOverSeeds c;
        c.bins = first.compute[i].bins;
        c.samples = first.compute[i].samples;
        c.paperSetting = first.compute[i].paperSetting;
        std::vector<double> angle, position, us;
        for (const SweepResults* r : runs) {
            if (i >= r->compute.size()) continue;
            angle.push_back(r->compute[i].angleError_deg);
            position.push_back(r->compute[i].positionError_mm);
            us.push_back(r->compute[i].microsecondsPerDecision);
        }
        c.angle_deg = overSeeds(angle, 0.0);
        c.position_mm = overSeeds(position, 0.0);
        c.microsecondsPerDecision = overSeeds(us, 0.0);
        out.compute.push_back(c);
    }
}

}  // namespace

SweepRates sweepRates(const std::vector<SeedOutcome>& all) {
    SweepRates out;
    Runs runs;
    for (const SeedOutcome& s : all)
        if (!s.failed() && !s.sweeps.empty()) runs.push_back(&s.sweeps);
    out.seeds = static_cast<int>(runs.size());
    if (runs.empty()) return out;
    addPerception(out, runs);
    addFollowing(out, runs);
    addBandit(out, runs);
    addRobustness(out, runs);
    addCompute(out, runs);
    return out;
}

}  // namespace activetouch
