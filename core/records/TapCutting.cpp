#include "core/records/TapCutting.h"

#include <algorithm>
#include <cmath>

#include "core/common/InputError.h"
#include "core/common/NumberText.h"

namespace activetouch {
namespace {

std::string lineName(int line) {
    return "line " + std::to_string(line);
}

}  // namespace

namespace {

double totalPressure(const SkinStream& s, std::size_t f) {
    double sum = 0.0;
    const double* v = s.frame(f);
    for (int k = 0; k < s.taxels; ++k) sum += v[k];
    return sum;
}

/// The tap in frames first..first+T-1; refuses a window with a frame missing.
TapRecord windowTap(const SkinStream& s, std::size_t first, const TapCutting& c,
                    const std::string& logPath, const std::string& which) {
    const double period = 1.0 / c.sampleRate_hz;
    TapRecord r;
    r.tap = Tap(c.samplesPerTap, s.taxels);
    r.ending = TapEnding::StrokeLimit;
    for (int t = 0; t < c.samplesPerTap; ++t) {
        const std::size_t f = first + static_cast<std::size_t>(t);
        if (t > 0 && (s.counters[f] != s.counters[f - 1] + 1 ||
                      s.times_s[f] - s.times_s[f - 1] > 1.5 * period))
            throw InputError(logPath, lineName(s.lines[f]),
                             which + " lacks a frame: after line " +
                                 std::to_string(s.lines[f - 1]) + " the counter goes " +
                                 std::to_string(s.counters[f - 1]) + " -> " +
                                 std::to_string(s.counters[f]) + " and the stamp " +
                                 numberText(s.times_s[f - 1]) + " -> " + numberText(s.times_s[f]) +
                                 " s inside the tap's window; a tap needs " +
                                 std::to_string(c.samplesPerTap) + " frames in a row");
        std::copy(s.frame(f), s.frame(f) + s.taxels,
                  r.tap.samples.data() + static_cast<std::size_t>(t * s.taxels));
        if (totalPressure(s, f) >= c.reflexThreshold) r.ending = TapEnding::ContactReflex;
    }
    r.startTime_s = s.times_s[first];
    r.cycleTime_s = c.samplesPerTap * period;
    return r;
}

}  // namespace

std::vector<TapRecord> cutTaps(const SkinStream& s, const std::vector<PoseLogEntry>* poses,
                               const TapCutting& c, const std::string& logPath,
                               const std::string& poseLogPath, std::string* cutOff) {
    std::vector<TapRecord> taps;
    const double period = 1.0 / c.sampleRate_hz;
    const std::size_t T = static_cast<std::size_t>(c.samplesPerTap);
    auto cutShort = [&](const std::string& what) {
        if (!cutOff)
            throw InputError(logPath, lineName(s.lines.back()),
                             what + "; the log ends before its window is whole");
        *cutOff = what + " is cut short by the end of the log and left out";
    };
    if (poses) {
        for (std::size_t i = 0; i < poses->size(); ++i) {
            const PoseLogEntry& p = (*poses)[i];
            const std::string which = "the tap of pose line " + std::to_string(p.line);
            const auto it =
                std::lower_bound(s.times_s.begin(), s.times_s.end(), p.time_s - 0.5 * period);
            const std::size_t first = static_cast<std::size_t>(it - s.times_s.begin());
            if (first + T > s.frameCount()) {
                if (i + 1 < poses->size())
                    throw InputError(poseLogPath, lineName((*poses)[i + 1].line),
                                     "the skin log " + logPath + " ends at " +
                                         numberText(s.times_s.back()) + " s, before " + which +
                                         " is whole, yet the pose log goes on: are they of the "
                                         "same session?");
                cutShort(which);
                break;
            }
            if (s.times_s[first] - p.time_s > 1.5 * period)
                throw InputError(poseLogPath, lineName(p.line),
                                 "the skin log " + logPath + " has no frame within " +
                                     numberText(1.5 * period) + " s of this tap's start (" +
                                     numberText(p.time_s) + " s; the next frame is at " +
                                     numberText(s.times_s[first]) +
                                     " s): are the logs on the same clock?");
            TapRecord r = windowTap(s, first, c, logPath, which);
            if (i + 1 < poses->size() &&
                s.times_s[first + T - 1] >= (*poses)[i + 1].time_s - 0.5 * period)
                throw InputError(poseLogPath, lineName((*poses)[i + 1].line),
                                 "this tap begins at " + numberText((*poses)[i + 1].time_s) +
                                     " s, inside the window of the tap before it (to " +
                                     numberText(s.times_s[first + T - 1]) +
                                     " s): taps are a window of " + std::to_string(T) +
                                     " frames apart at least");
            r.pose = p.pose;
            r.startTime_s = p.time_s;
            r.cycleTime_s =
                (i + 1 < poses->size() ? (*poses)[i + 1].time_s - p.time_s : r.cycleTime_s);
            taps.push_back(std::move(r));
        }
        return taps;
    }
    const std::size_t lead = static_cast<std::size_t>(std::max(0, c.leadFrames));
    bool below = true;
    for (std::size_t f = 0; f < s.frameCount(); ++f) {
        const bool touching = totalPressure(s, f) >= c.reflexThreshold;
        if (!(touching && below)) {
            below = !touching;
            continue;
        }
        below = false;
        const std::string which =
            "the tap crossing the reflex threshold at line " + std::to_string(s.lines[f]);
        if (f < lead) continue;  // began before the log did
        const std::size_t first = f - lead;
        if (first + T > s.frameCount()) {
            cutShort(which);
            break;
        }
        TapRecord r = windowTap(s, first, c, logPath, which);
        r.pose = {std::nan(""), std::nan("")};
        taps.push_back(std::move(r));
        // The next tap starts after this window.
        f = first + T - 1;
        below = totalPressure(s, f) < c.reflexThreshold;
    }
    return taps;
}

std::vector<CollectedTap> labelProtocolTaps(const std::vector<TapRecord>& taps, bool posesLogged,
                                            const std::vector<PoseLogEntry>& poseLines,
                                            const Polygon& object, const ClassSet& classes,
                                            const TrainingProtocolSettings& protocol,
                                            const std::string& poseLogPath,
                                            const std::string& logPath, double tolerance_mm) {
    const auto sites = edgeSites(object, classes);
    const std::size_t planned = static_cast<std::size_t>(protocol.dataSets) *
                                static_cast<std::size_t>(classes.classCount()) *
                                static_cast<std::size_t>(protocol.tapsPerClass);
    if (taps.size() > planned)
        throw InputError(posesLogged ? poseLogPath : logPath, "",
                         "holds " + std::to_string(taps.size()) +
                             " taps, but the experiment's training protocol takes " +
                             std::to_string(planned) + " (" + std::to_string(protocol.dataSets) +
                             " data sets x " + std::to_string(classes.classCount()) +
                             " classes x " + std::to_string(protocol.tapsPerClass) +
                             "): import with the experiment the taps were taken for");
    const double reach = tolerance_mm + 4.0 * std::sqrt(2.0) * protocol.placementJitter_mm;
    std::vector<CollectedTap> out;
    out.reserve(taps.size());
    std::size_t k = 0;
    for (int set = 1; set <= protocol.dataSets; ++set) {
        const double shift = protocol.isTrainingSet(set) ? 0.0 : protocol.testOffset_mm;
        for (std::size_t o = 0; o < sites.size(); ++o)
            for (int p = 1; p <= classes.positions; ++p)
                for (int r = 0; r < protocol.tapsPerClass; ++r, ++k) {
                    if (k == taps.size()) return out;
                    const double offset = classes.offsetOf(p) + shift;
                    const Vec2 planned = sites[o].poseAt(offset);
                    CollectedTap c;
                    c.record = taps[k];
                    c.dataSet = set;
                    c.cls = classes.classOf(static_cast<int>(o), p);
                    if (posesLogged) {
                        const double off = distance(c.record.pose, planned);
                        if (!(off <= reach))
                            throw InputError(
                                poseLogPath, lineName(poseLines[k].line),
                                "tap " + std::to_string(k + 1) + " was taken at (" +
                                    numberText(c.record.pose.x) + ", " +
                                    numberText(c.record.pose.y) +
                                    ") mm, but the protocol takes its tap " +
                                    std::to_string(k + 1) + " (set " + std::to_string(set) +
                                    ", edge " + numberText(classes.orientationDegOf(c.cls)) +
                                    " deg, position " + std::to_string(p) + ") at (" +
                                    numberText(planned.x) + ", " + numberText(planned.y) +
                                    ") mm, " + numberText(off) + " mm away (at most " +
                                    numberText(reach) +
                                    " with the placement jitter): is the log of another "
                                    "experiment or object placement?");
                        c.trueOffset_mm = sites[o].offsetOf(c.record.pose);
                    } else {
                        c.record.pose = planned;
                        c.trueOffset_mm = offset;
                    }
                    out.push_back(std::move(c));
                }
    }
    return out;
}

}  // namespace activetouch
