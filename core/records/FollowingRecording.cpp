#include "core/records/FollowingRecording.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "core/common/InputError.h"
#include "core/io/Csv.h"
#include "core/io/InputFile.h"

namespace activetouch {
namespace {

const char* kFixedColumns[] = {"shape",
                               "mode",
                               "trial",
                               "tap",
                               "pose_x_mm",
                               "pose_y_mm",
                               "robot_time_s",
                               "ending",
                               "contact",
                               "shape_class",
                               "orientation_deg",
                               "position",
                               "offset_mm",
                               "posterior",
                               "rule",
                               "move_x_mm",
                               "move_y_mm",
                               "progress_mm",
                               "contour_distance_mm",
                               "sample"};
constexpr int kFixed = 20;
enum Column {
    kShape,
    kMode,
    kTrial,
    kTap,
    kPoseX,
    kPoseY,
    kTime,
    kEnding,
    kContact,
    kShapeClass,
    kOrientation,
    kPosition,
    kOffset,
    kPosterior,
    kRule,
    kMoveX,
    kMoveY,
    kSample = 19
};

}  // namespace

FollowingRecording::FollowingRecording(const std::string& path, int taxels)
    : file_(path), taxels_(taxels) {
    writeTapTableHeader(file_, kFixedColumns, kFixed, taxels);
}

void FollowingRecording::append(const std::string& label, FollowingMode mode, int trial,
                                int tapIndex, const FollowedTap& t) {
    const TapRecord& r = t.record;
    const Vec2 move = t.decision.move();
    const std::string shapeClass = t.percept.shapeClass();
    for (int s = 0; s < r.tap.sampleCount(); ++s) {
        file_.print(
            "%s,%s,%d,%d,%.17g,%.17g,%.17g,%s,%d,%s,%g,%d,%g,%.10g,%s,%.17g,%.17g,%.10g,%.10g,%d",
            label.c_str(), modeName(mode), trial, tapIndex, r.pose.x, r.pose.y, r.startTime_s,
            r.ending == TapEnding::ContactReflex ? "reflex" : "stroke_limit", t.contact ? 1 : 0,
            shapeClass.c_str(), t.percept.orientationDeg, t.percept.position, t.percept.offset_mm,
            t.percept.posterior, ruleFor(t.decision.rule).name, move.x, move.y, t.progress_mm,
            t.contourDistance_mm, s);
        for (int k = 0; k < taxels_; ++k) file_.print(",%.17g", r.tap.at(s, k));
        file_.put('\n');
    }
    file_.flush();
}

namespace {

/// Reads and checks `path`; with `trials`, keeps every whole tap.
FollowingRecordingContents parseFollowingRecording(const std::string& path,
                                                   std::vector<RecordedTrial>* trials,
                                                   const RecordingBounds& bounds) {
    std::ifstream in = openRecording(path);
    RecordingRows rows(in, path);
    const auto& header = rows.header();
    const int taxels = static_cast<int>(header.size()) - kFixed;
    bool ok = taxels >= 1;
    for (int i = 0; ok && i < kFixed; ++i)
        ok = header[static_cast<std::size_t>(i)] == kFixedColumns[i];
    for (int k = 0; ok && k < taxels; ++k)
        ok = header[static_cast<std::size_t>(kFixed + k)] == "taxel_" + std::to_string(k);
    if (!ok)
        throw InputError(path, "line 1",
                         "unexpected columns; a following recording starts with shape,mode,trial,"
                         "tap,... and ends with sample,taxel_0,...,taxel_11");

    FollowingRecordingContents contents;
    checkTaxelCount(taxels, bounds, path);
    contents.samplesPerTap = bounds.samplesPerTap;
    int lineNo = 1;
    std::vector<std::string> first;  // the tap's first row: its own columns hold on every row
    int firstLine = 0;
    double lastTime = 0.0;  // within a trial
    // The tap being read: its trial, its index and how many samples came so far.
    std::string trialKey;
    int tapIndex = -1, samples = 0;
    auto at = [&](const char* column) {
        return "line " + std::to_string(lineNo) + ", column " + column;
    };
    int lastRow = 0;    // the line of the tap's last sample so far
    TapRecord tapRead;  // the tap being read, when its samples are kept
    RecordedDecision decisionRead;
    auto finishTap = [&]() {
        if (samples == 0) return;
        if (contents.samplesPerTap == 0) contents.samplesPerTap = samples;
        if (samples != contents.samplesPerTap)
            throw InputError(path, "line " + std::to_string(lastRow),
                             "the tap above has " + std::to_string(samples) +
                                 " samples, the first tap " +
                                 std::to_string(contents.samplesPerTap));
        ++contents.taps;
        if (trials) {
            trials->back().taps.push_back(std::move(tapRead));
            trials->back().decisions.push_back(decisionRead);
        }
    };
    std::vector<std::string> f;
    while (rows.next(f)) {
        lineNo = rows.line();
        std::vector<double> v(f.size(), 0.0);
        for (int i = 0; i < kFixed + taxels; ++i) {
            if (i == kShape || i == kMode || i == kEnding || i == kShapeClass || i == kRule)
                continue;
            const std::string& column = header[static_cast<std::size_t>(i)];  // checked above
            const std::string& field = f[static_cast<std::size_t>(i)];
            const bool counts = i == kTrial || i == kTap || i == kPosition || i == kSample;
            v[static_cast<std::size_t>(i)] = counts ? csvInteger(field, path, lineNo, column)
                                                    : csvNumber(field, path, lineNo, column);
            if (i >= kFixed &&
                (v[static_cast<std::size_t>(i)] < 0.0 || v[static_cast<std::size_t>(i)] > 255.0))
                throw InputError(path, at(column.c_str()),
                                 "pressure " + f[static_cast<std::size_t>(i)] +
                                     " is outside the fingertip's 0..255 counts");
        }
        if (!modeNamed(f[kMode]))
            throw InputError(path, at("mode"), "'" + f[kMode] + "' is neither active nor passive");
        if (f[kEnding] != "reflex" && f[kEnding] != "stroke_limit")
            throw InputError(path, at("ending"),
                             "'" + f[kEnding] + "' is neither reflex nor stroke_limit");
        if (f[kContact] != "0" && f[kContact] != "1")
            throw InputError(path, at("contact"), "'" + f[kContact] + "' is neither 0 nor 1");
        bool knownRule = false;
        for (const auto& r : decisionRules()) knownRule = knownRule || f[kRule] == r.name;
        if (!knownRule)
            throw InputError(path, at("rule"),
                             "'" + f[kRule] + "' is not a rule of the decision table");
        const std::string key = f[kShape] + "," + f[kMode] + "," + f[kTrial];
        const int tap = static_cast<int>(v[kTap]), sample = static_cast<int>(v[kSample]);
        if (sample == 0) {
            finishTap();
            if (v[kPosterior] < 0.0 || v[kPosterior] > 1.0)
                throw InputError(path, at("posterior"),
                                 "posterior " + f[kPosterior] +
                                     " is not a probability (0 to 1)");
            if (std::abs(v[kOrientation]) > 360.0)
                throw InputError(path, at("orientation_deg"),
                                 "orientation " + f[kOrientation] + " deg is beyond +-360");
            const double reach = std::max(bounds.travel_mm.x, bounds.travel_mm.y);
            for (int c : {kOffset, kMoveX, kMoveY})
                if (std::abs(v[static_cast<std::size_t>(c)]) > reach)
                    throw InputError(path, at(kFixedColumns[c]),
                                     std::string(kFixedColumns[c]) + " " +
                                         f[static_cast<std::size_t>(c)] +
                                         " mm reaches beyond the stage travel");
            checkPose({v[kPoseX], v[kPoseY]}, bounds, path, lineNo, f[kPoseX], f[kPoseY]);
            checkTime(v[kTime], key == trialKey ? lastTime : 0.0, path, lineNo, f[kTime]);
            lastTime = v[kTime];
            first.assign(f.begin(), f.begin() + kSample);
            firstLine = lineNo;
            const int expected = key == trialKey ? tapIndex + 1 : 0;
            if (tap != expected)
                throw InputError(path, at("tap"),
                                 "tap " + f[kTap] + " follows " +
                                     (key == trialKey ? "tap " + std::to_string(tapIndex)
                                                      : std::string("another trial")) +
                                     "; a trial's taps run 0, 1, 2, ... in order");
            if (key != trialKey) {
                ++contents.trials;
                if (trials)
                    trials->push_back(
                        {f[kShape], *modeNamed(f[kMode]), static_cast<int>(v[kTrial]), {}, {}});
            }
            trialKey = key;
            tapIndex = tap;
            samples = 0;
            if (trials) {
                tapRead = TapRecord{};
                tapRead.tap.taxels = taxels;
                tapRead.pose = {v[kPoseX], v[kPoseY]};
                tapRead.startTime_s = v[kTime];
                tapRead.ending =
                    f[kEnding] == "reflex" ? TapEnding::ContactReflex : TapEnding::StrokeLimit;
                decisionRead = {f[kShapeClass], static_cast<int>(v[kPosition]), f[kRule]};
            }
        } else if (key != trialKey || tap != tapIndex || sample != samples) {
            throw InputError(path, at("sample"),
                             "sample " + f[kSample] +
                                 " does not continue the tap above it; each tap's samples run 0, "
                                 "1, 2, ... in order");
        } else {
            sameAsFirstRow(f, first, kFixedColumns, kSample, path, lineNo, firstLine);
        }
        if (bounds.samplesPerTap > 0 && samples >= contents.samplesPerTap)
            throw InputError(path, at("sample"),
                             "the tap has more than " + std::to_string(contents.samplesPerTap) +
                                 " samples, as many as the run's run.json gives");
        ++samples;
        lastRow = lineNo;
        if (trials)
            tapRead.tap.samples.insert(tapRead.tap.samples.end(), v.begin() + kFixed,
                                       v.begin() + kFixed + taxels);
    }
    // The last tap: whole, or cut short by a run that stopped while writing it.
    if (samples > 0 && contents.samplesPerTap > 0 && samples < contents.samplesPerTap) {
        contents.cutOff = "the last tap (" + trialKey + ", tap " + std::to_string(tapIndex) +
                          ") has " + std::to_string(samples) + " of " +
                          std::to_string(contents.samplesPerTap) + " samples";
        if (tapIndex == 0) {
            --contents.trials;
            if (trials) trials->pop_back();
        }
    } else {
        finishTap();
    }
    if (!rows.cutOff().empty())
        contents.cutOff =
            (contents.cutOff.empty() ? std::string() : contents.cutOff + "; ") + rows.cutOff();
    if (contents.taps == 0) throw InputError(path, "line 2", "the file holds no whole tap");
    return contents;
}

}  // namespace

FollowingRecordingContents checkFollowingRecording(const std::string& path,
                                                   const RecordingBounds& bounds) {
    return parseFollowingRecording(path, nullptr, bounds);
}

std::vector<RecordedTrial> readFollowingRecording(const std::string& path,
                                                  FollowingRecordingContents* contents,
                                                  const RecordingBounds& bounds) {
    std::vector<RecordedTrial> trials;
    const FollowingRecordingContents c = parseFollowingRecording(path, &trials, bounds);
    if (contents) *contents = c;
    return trials;
}

}  // namespace activetouch
