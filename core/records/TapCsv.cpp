#include "core/records/TapCsv.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/common/InputError.h"
#include "core/io/Csv.h"
#include "core/io/InputFile.h"

namespace activetouch {
namespace {

const char* kFixedColumns[] = {
    "set",       "class",        "orientation_deg", "position",      "true_offset_mm", "pose_x_mm",
    "pose_y_mm", "robot_time_s", "ending",          "stop_depth_mm", "sample"};
constexpr int kFixed = 11;  // set .. stop_depth_mm the same on every row of a tap, then sample
// Recordings written before the stop depth was kept have every column but that one.
const char* kEarlierColumns[] = {
    "set",       "class",     "orientation_deg", "position", "true_offset_mm",
    "pose_x_mm", "pose_y_mm", "robot_time_s",    "ending",   "sample"};
constexpr int kEarlierFixed = 10;

}  // namespace

TapCsvWriter::TapCsvWriter(const std::string& path, int taxels) : file_(path), taxels_(taxels) {
    writeTapTableHeader(file_, kFixedColumns, kFixed, taxels);
}

void TapCsvWriter::append(const CollectedTap& c, const ClassSet& classes) {
    const TapRecord& r = c.record;
    const char* ending = r.ending == TapEnding::ContactReflex ? "reflex" : "stroke_limit";
    for (int t = 0; t < r.tap.sampleCount(); ++t) {
        file_.print("%d,%d,%.17g,%d,%.17g,%.17g,%.17g,%.17g,%s,%.17g,%d", c.dataSet, c.cls,
                    classes.orientationDegOf(c.cls), classes.positionOf(c.cls), c.trueOffset_mm,
                    r.pose.x, r.pose.y, r.startTime_s, ending, r.stopDepth_mm, t);
        for (int k = 0; k < taxels_; ++k) file_.print(",%.17g", r.tap.at(t, k));
        file_.put('\n');
    }
    file_.flush();
}

namespace {

/// The columns a tap file's header holds: the present layout, or the earlier one without the
/// stop depth (read as not recorded, 0).
struct TapLayout {
    bool earlier = false;
    const char* const* columns = kFixedColumns;
    int fixed = kFixed;
    int taxels = 0;
    int perTap() const { return fixed - 1; }
    std::size_t sampleColumn() const { return static_cast<std::size_t>(fixed - 1); }
};

TapLayout tapLayoutOf(const std::vector<std::string>& header, const std::string& path) {
    TapLayout l;
    l.earlier = header.size() > 9 && header[9] == "sample";
    l.columns = l.earlier ? kEarlierColumns : kFixedColumns;
    l.fixed = l.earlier ? kEarlierFixed : kFixed;
    l.taxels = static_cast<int>(header.size()) - l.fixed;
    bool ok = l.taxels >= 1;
    for (int i = 0; ok && i < l.fixed; ++i)
        ok = header[static_cast<std::size_t>(i)] == l.columns[i];
    for (int k = 0; ok && k < l.taxels; ++k)
        ok = header[static_cast<std::size_t>(l.fixed + k)] == "taxel_" + std::to_string(k);
    if (ok) return l;
    std::string expected;
    for (const char* c : kFixedColumns) expected += std::string(c) + ",";
    const bool following = !header.empty() && header[0] == "shape";
    throw InputError(path, "line 1",
                     "unexpected columns; a tap file starts with " + expected +
                         "taxel_0,...,taxel_11" +
                         (following ? " (this is a contour-following recording; the training "
                                      "taps are in the run's data/taps.csv)"
                                    : ""));
}

/// Reads a tap file row by row: each tap's first row (sample 0) gives its per-tap columns,
/// which every later row of the tap repeats, and every row one frame.
class TapCsvReader {
public:
    TapCsvReader(const std::string& path, const ClassSet& classes, const RecordingBounds& bounds,
                 RecordingRows& rows)
        : path_(path),
          classes_(classes),
          bounds_(bounds),
          rows_(rows),
          layout_(tapLayoutOf(rows.header(), path)),
          samplesPerTap_(bounds.samplesPerTap) {
        checkTaxelCount(layout_.taxels, bounds, path);
    }

    void readRows() {
        std::vector<std::string> f;
        while (rows_.next(f)) {
            line_ = rows_.line();
            const int set = integer(f[0], "set");
            if (set < 1)
                throw at("set", "data set " + f[0] + " is below 1; data sets are numbered from 1");
            const int cls = classOf(f);
            const int sample = integer(f[layout_.sampleColumn()], "sample");
            if (sample == 0) {
                finishTap();
                startTap(f, set, cls);
            } else if (taps_.empty() || sample != static_cast<int>(samples_.size()) ||
                       taps_.back().cls != cls || taps_.back().dataSet != set) {
                throw at("sample", "sample " + f[layout_.sampleColumn()] +
                                       " does not continue the tap above it; each tap's samples "
                                       "run 0, 1, 2, ... in order");
            } else {
                sameAsFirstRow(f, first_, layout_.columns, layout_.perTap(), path_, line_,
                               firstLine_);
            }
            if (bounds_.samplesPerTap > 0 && static_cast<int>(samples_.size()) >= samplesPerTap_)
                throw at("sample", "the tap has more than " + std::to_string(samplesPerTap_) +
                                       " samples, as many as the run's run.json gives");
            samples_.push_back(frameOf(f));
            lastRow_ = line_;
        }
    }

    /// The taps read; the last one dropped, and said in `cutOff`, where it was cut short.
    std::vector<CollectedTap> finish(std::string* cutOff) {
        std::string cut;
        if (!taps_.empty() && samplesPerTap_ > 0 &&
            static_cast<int>(samples_.size()) < samplesPerTap_) {
            const CollectedTap& last = taps_.back();
            cut = "the last tap (set " + std::to_string(last.dataSet) + ", class " +
                  std::to_string(last.cls) + ") has " + std::to_string(samples_.size()) + " of " +
                  std::to_string(samplesPerTap_) + " samples";
            taps_.pop_back();
        } else {
            finishTap();
        }
        if (!rows_.cutOff().empty())
            cut = (cut.empty() ? std::string() : cut + "; ") + rows_.cutOff();
        if (taps_.empty()) throw InputError(path_, "line 2", "the file holds no whole tap");
        if (!cut.empty()) {
            if (!cutOff)
                throw InputError(path_, "the end",
                                 cut +
                                     "; the recording was cut short, as by a run stopped while "
                                     "writing");
            *cutOff = cut;
        }
        return std::move(taps_);
    }

private:
    InputError at(const std::string& column, const std::string& what) const {
        return InputError(path_, "line " + std::to_string(line_) + ", column " + column, what);
    }
    double number(const std::string& field, const std::string& column) const {
        return csvNumber(field, path_, line_, column);
    }
    int integer(const std::string& field, const std::string& column) const {
        return csvInteger(field, path_, line_, column);
    }

    /// The row's class, held to the orientation and position it names: a class number means
    /// them only within its class set, so a row naming others was recorded with other classes.
    int classOf(const std::vector<std::string>& f) const {
        const int cls = integer(f[1], "class");
        if (cls < 0 || cls >= classes_.classCount())
            throw at("class", "class " + f[1] + " is outside 0.." +
                                  std::to_string(classes_.classCount() - 1) +
                                  " for this experiment's classes");
        const double orientation = number(f[2], "orientation_deg");
        const int position = integer(f[3], "position");
        if (orientation != classes_.orientationDegOf(cls) || position != classes_.positionOf(cls))
            throw at("class", "class " + f[1] + " is the " +
                                  ClassSet::orientationName(classes_.orientationDegOf(cls)) +
                                  " edge at position " + std::to_string(classes_.positionOf(cls)) +
                                  " in these classes, but the row says orientation " + f[2] +
                                  " deg, position " + f[3] +
                                  "; the taps were recorded with other classes: give the "
                                  "experiment they were recorded with");
        return cls;
    }

    void startTap(const std::vector<std::string>& f, int set, int cls) {
        CollectedTap c;
        c.dataSet = set;
        c.cls = cls;
        c.trueOffset_mm = number(f[4], "true_offset_mm");
        if (std::abs(c.trueOffset_mm) > std::max(bounds_.travel_mm.x, bounds_.travel_mm.y))
            throw at("true_offset_mm",
                     "an offset of " + f[4] + " mm from the edge is beyond the stage");
        c.record.pose = {number(f[5], "pose_x_mm"), number(f[6], "pose_y_mm")};
        checkPose(c.record.pose, bounds_, path_, line_, f[5], f[6]);
        c.record.startTime_s = number(f[7], "robot_time_s");
        checkTime(c.record.startTime_s, lastTime_, path_, line_, f[7]);
        lastTime_ = c.record.startTime_s;
        first_.assign(f.begin(), f.begin() + layout_.perTap());
        firstLine_ = line_;
        if (f[8] != "reflex" && f[8] != "stroke_limit")
            throw at("ending", "'" + f[8] + "' is neither reflex nor stroke_limit");
        c.record.ending = f[8] == "reflex" ? TapEnding::ContactReflex : TapEnding::StrokeLimit;
        if (!layout_.earlier) {
            c.record.stopDepth_mm = number(f[9], "stop_depth_mm");
            if (c.record.stopDepth_mm < 0.0 || c.record.stopDepth_mm > 100.0)
                throw at("stop_depth_mm", "a stop depth of " + f[9] +
                                              " mm is not an indentation (0 for none, up to the "
                                              "stroke, never over 100 mm)");
        }
        taps_.push_back(c);
    }

    std::vector<double> frameOf(const std::vector<std::string>& f) const {
        const auto& header = rows_.header();
        std::vector<double> frame(static_cast<std::size_t>(layout_.taxels));
        for (int k = 0; k < layout_.taxels; ++k) {
            const auto i = static_cast<std::size_t>(layout_.fixed + k);
            const double v = number(f[i], header[i]);
            if (v < 0.0 || v > 255.0)
                throw at(header[i],
                         "pressure " + f[i] + " is outside the fingertip's 0..255 counts");
            frame[static_cast<std::size_t>(k)] = v;
        }
        return frame;
    }

    /// The frames read since the tap's first row into the tap, held to the first tap's length.
    void finishTap() {
        if (taps_.empty()) return;
        if (samplesPerTap_ == 0) samplesPerTap_ = static_cast<int>(samples_.size());
        if (static_cast<int>(samples_.size()) != samplesPerTap_)
            throw InputError(path_, "line " + std::to_string(lastRow_),
                             "the tap above has " + std::to_string(samples_.size()) +
                                 " samples, the first tap " + std::to_string(samplesPerTap_) +
                                 "; every tap of a recording has as many");
        Tap& t = taps_.back().record.tap;
        t = Tap(static_cast<int>(samples_.size()), layout_.taxels);
        for (std::size_t s = 0; s < samples_.size(); ++s)
            for (int k = 0; k < layout_.taxels; ++k)
                t.at(static_cast<int>(s), k) = samples_[s][static_cast<std::size_t>(k)];
        samples_.clear();
    }

    const std::string& path_;
    const ClassSet& classes_;
    const RecordingBounds& bounds_;
    RecordingRows& rows_;
    const TapLayout layout_;
    std::vector<CollectedTap> taps_;
    std::vector<std::vector<double>> samples_;
    int samplesPerTap_ = 0, lastRow_ = 0, line_ = 1, firstLine_ = 0;
    std::vector<std::string> first_;  ///< the tap's first row
    double lastTime_ = 0.0;
};

}  // namespace

std::vector<CollectedTap> readTapCsv(const std::string& path, const ClassSet& classes,
                                     std::string* cutOff, const RecordingBounds& bounds) {
    std::ifstream in = openRecording(path);
    RecordingRows rows(in, path);
    TapCsvReader reader(path, classes, bounds, rows);
    reader.readRows();
    return reader.finish(cutOff);
}

}  // namespace activetouch
