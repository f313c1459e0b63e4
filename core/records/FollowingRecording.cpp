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

int taxelsOfHeader(const std::vector<std::string>& header, const std::string& path) {
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
    return taxels;
}

/// Reads and checks a following recording row by row; with `trials`, keeps every whole tap.
class FollowingReader {
public:
    FollowingReader(const std::string& path, std::vector<RecordedTrial>* trials,
                    const RecordingBounds& bounds, RecordingRows& rows)
        : path_(path),
          trials_(trials),
          bounds_(bounds),
          rows_(rows),
          taxels_(taxelsOfHeader(rows.header(), path)) {
        checkTaxelCount(taxels_, bounds, path);
        contents_.samplesPerTap = bounds.samplesPerTap;
    }

    void readRows() {
        std::vector<std::string> f;
        while (rows_.next(f)) {
            line_ = rows_.line();
            const std::vector<double> v = valuesOf(f);
            const std::string key = f[kShape] + "," + f[kMode] + "," + f[kTrial];
            const int tap = static_cast<int>(v[kTap]), sample = static_cast<int>(v[kSample]);
            if (sample == 0) {
                finishTap();
                startTap(f, v, key, tap);
            } else if (key != trialKey_ || tap != tapIndex_ || sample != samples_) {
                throw InputError(path_, at("sample"),
                                 "sample " + f[kSample] +
                                     " does not continue the tap above it; each tap's samples "
                                     "run 0, 1, 2, ... in order");
            } else {
                sameAsFirstRow(f, first_, kFixedColumns, kSample, path_, line_, firstLine_);
            }
            if (bounds_.samplesPerTap > 0 && samples_ >= contents_.samplesPerTap)
                throw InputError(path_, at("sample"),
                                 "the tap has more than " +
                                     std::to_string(contents_.samplesPerTap) +
                                     " samples, as many as the run's run.json gives");
            ++samples_;
            lastRow_ = line_;
            if (trials_)
                tapRead_.tap.samples.insert(tapRead_.tap.samples.end(), v.begin() + kFixed,
                                            v.begin() + kFixed + taxels_);
        }
    }

    /// What was read; the last tap left out, and said, where it was cut short.
    FollowingRecordingContents finish() {
        if (samples_ > 0 && contents_.samplesPerTap > 0 && samples_ < contents_.samplesPerTap) {
            contents_.cutOff = "the last tap (" + trialKey_ + ", tap " + std::to_string(tapIndex_) +
                               ") has " + std::to_string(samples_) + " of " +
                               std::to_string(contents_.samplesPerTap) + " samples";
            if (tapIndex_ == 0) {
                --contents_.trials;
                if (trials_) trials_->pop_back();
            }
        } else {
            finishTap();
        }
        if (!rows_.cutOff().empty())
            contents_.cutOff =
                (contents_.cutOff.empty() ? std::string() : contents_.cutOff + "; ") +
                rows_.cutOff();
        if (contents_.taps == 0) throw InputError(path_, "line 2", "the file holds no whole tap");
        return contents_;
    }

private:
    std::string at(const char* column) const {
        return "line " + std::to_string(line_) + ", column " + column;
    }

    /// The row's numbers by column (0 for the named columns), with its names checked.
    std::vector<double> valuesOf(const std::vector<std::string>& f) const {
        const auto& header = rows_.header();
        std::vector<double> v(f.size(), 0.0);
        for (int i = 0; i < kFixed + taxels_; ++i) {
            if (i == kShape || i == kMode || i == kEnding || i == kShapeClass || i == kRule)
                continue;
            const std::string& column = header[static_cast<std::size_t>(i)];  // checked
            const std::string& field = f[static_cast<std::size_t>(i)];
            const bool counts = i == kTrial || i == kTap || i == kPosition || i == kSample;
            const double x = counts ? csvInteger(field, path_, line_, column)
                                    : csvNumber(field, path_, line_, column);
            if (i >= kFixed && (x < 0.0 || x > 255.0))
                throw InputError(path_, at(column.c_str()),
                                 "pressure " + field + " is outside the fingertip's 0..255 counts");
            v[static_cast<std::size_t>(i)] = x;
        }
        if (!modeNamed(f[kMode]))
            throw InputError(path_, at("mode"), "'" + f[kMode] + "' is neither active nor passive");
        if (f[kEnding] != "reflex" && f[kEnding] != "stroke_limit")
            throw InputError(path_, at("ending"),
                             "'" + f[kEnding] + "' is neither reflex nor stroke_limit");
        if (f[kContact] != "0" && f[kContact] != "1")
            throw InputError(path_, at("contact"), "'" + f[kContact] + "' is neither 0 nor 1");
        bool knownRule = false;
        for (const auto& r : decisionRules()) knownRule = knownRule || f[kRule] == r.name;
        if (!knownRule)
            throw InputError(path_, at("rule"),
                             "'" + f[kRule] + "' is not a rule of the decision table");
        return v;
    }

    /// A tap's first row: its percept and move within bounds, its place in its trial.
    void checkTapStart(const std::vector<std::string>& f, const std::vector<double>& v,
                       const std::string& key, int tap) {
        if (v[kPosterior] < 0.0 || v[kPosterior] > 1.0)
            throw InputError(path_, at("posterior"),
                             "posterior " + f[kPosterior] + " is not a probability (0 to 1)");
        if (std::abs(v[kOrientation]) > 360.0)
            throw InputError(path_, at("orientation_deg"),
                             "orientation " + f[kOrientation] + " deg is beyond +-360");
        const double reach = std::max(bounds_.travel_mm.x, bounds_.travel_mm.y);
        for (int c : {kOffset, kMoveX, kMoveY})
            if (std::abs(v[static_cast<std::size_t>(c)]) > reach)
                throw InputError(path_, at(kFixedColumns[c]),
                                 std::string(kFixedColumns[c]) + " " +
                                     f[static_cast<std::size_t>(c)] +
                                     " mm reaches beyond the stage travel");
        checkPose({v[kPoseX], v[kPoseY]}, bounds_, path_, line_, f[kPoseX], f[kPoseY]);
        checkTime(v[kTime], key == trialKey_ ? lastTime_ : 0.0, path_, line_, f[kTime]);
        lastTime_ = v[kTime];
        const int expected = key == trialKey_ ? tapIndex_ + 1 : 0;
        if (tap != expected)
            throw InputError(path_, at("tap"),
                             "tap " + f[kTap] + " follows " +
                                 (key == trialKey_ ? "tap " + std::to_string(tapIndex_)
                                                   : std::string("another trial")) +
                                 "; a trial's taps run 0, 1, 2, ... in order");
    }

    void startTap(const std::vector<std::string>& f, const std::vector<double>& v,
                  const std::string& key, int tap) {
        checkTapStart(f, v, key, tap);
        first_.assign(f.begin(), f.begin() + kSample);
        firstLine_ = line_;
        if (key != trialKey_) {
            ++contents_.trials;
            if (trials_)
                trials_->push_back(
                    {f[kShape], *modeNamed(f[kMode]), static_cast<int>(v[kTrial]), {}, {}});
        }
        trialKey_ = key;
        tapIndex_ = tap;
        samples_ = 0;
        if (!trials_) return;
        tapRead_ = TapRecord{};
        tapRead_.tap.taxels = taxels_;
        tapRead_.pose = {v[kPoseX], v[kPoseY]};
        tapRead_.startTime_s = v[kTime];
        tapRead_.ending =
            f[kEnding] == "reflex" ? TapEnding::ContactReflex : TapEnding::StrokeLimit;
        decisionRead_ = {f[kShapeClass], static_cast<int>(v[kPosition]), f[kRule]};
    }

    void finishTap() {
        if (samples_ == 0) return;
        if (contents_.samplesPerTap == 0) contents_.samplesPerTap = samples_;
        if (samples_ != contents_.samplesPerTap)
            throw InputError(path_, "line " + std::to_string(lastRow_),
                             "the tap above has " + std::to_string(samples_) +
                                 " samples, the first tap " +
                                 std::to_string(contents_.samplesPerTap));
        ++contents_.taps;
        if (trials_) {
            trials_->back().taps.push_back(std::move(tapRead_));
            trials_->back().decisions.push_back(decisionRead_);
        }
    }

    const std::string& path_;
    std::vector<RecordedTrial>* trials_;
    const RecordingBounds& bounds_;
    RecordingRows& rows_;
    const int taxels_;
    FollowingRecordingContents contents_;
    int line_ = 1, firstLine_ = 0, lastRow_ = 0;
    std::vector<std::string> first_;  ///< the tap's first row: its own columns hold on every row
    double lastTime_ = 0.0;           ///< within a trial
    // The tap being read: its trial, its index and how many samples came so far.
    std::string trialKey_;
    int tapIndex_ = -1, samples_ = 0;
    TapRecord tapRead_;  ///< the tap being read, when its samples are kept
    RecordedDecision decisionRead_;
};

/// Reads and checks `path`; with `trials`, keeps every whole tap.
FollowingRecordingContents parseFollowingRecording(const std::string& path,
                                                   std::vector<RecordedTrial>* trials,
                                                   const RecordingBounds& bounds) {
    std::ifstream in = openRecording(path);
    RecordingRows rows(in, path);
    FollowingReader reader(path, trials, bounds, rows);
    reader.readRows();
    return reader.finish();
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
