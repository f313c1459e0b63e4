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

std::vector<CollectedTap> readTapCsv(const std::string& path, const ClassSet& classes,
                                     std::string* cutOff, const RecordingBounds& bounds) {
    std::ifstream in = openRecording(path);
    RecordingRows rows(in, path);
    const auto& header = rows.header();
    // The present layout, or the earlier one without the stop depth (read as not recorded, 0).
    const bool earlier = header.size() > 9 && header[9] == "sample";
    const char* const* columns = earlier ? kEarlierColumns : kFixedColumns;
    const int fixed = earlier ? kEarlierFixed : kFixed;
    const int perTap = fixed - 1;
    const auto sampleColumn = static_cast<std::size_t>(fixed - 1);
    int taxels = static_cast<int>(header.size()) - fixed;
    bool ok = taxels >= 1;
    for (int i = 0; ok && i < fixed; ++i) ok = header[static_cast<std::size_t>(i)] == columns[i];
    for (int k = 0; ok && k < taxels; ++k)
        ok = header[static_cast<std::size_t>(fixed + k)] == "taxel_" + std::to_string(k);
    if (!ok) {
        std::string expected;
        for (const char* c : kFixedColumns) expected += std::string(c) + ",";
        const bool following = !header.empty() && header[0] == "shape";
        throw InputError(
            path, "line 1",
            "unexpected columns; a tap file starts with " + expected + "taxel_0,...,taxel_11" +
                (following ? " (this is a contour-following recording; the training taps are in "
                             "the run's data/taps.csv)"
                           : ""));
    }
    checkTaxelCount(taxels, bounds, path);
    std::vector<CollectedTap> taps;
    std::vector<std::vector<double>> samples;
    int lineNo = 1;
    auto number = [&](const std::string& field, const std::string& column) {
        return csvNumber(field, path, lineNo, column);
    };
    auto integer = [&](const std::string& field, const std::string& column) {
        return csvInteger(field, path, lineNo, column);
    };
    int samplesPerTap = bounds.samplesPerTap, lastRow = 0;
    std::vector<std::string> first;  // the tap's first row: its per-tap columns hold on every row
    int firstLine = 0;
    double lastTime = 0.0;
    auto finishTap = [&]() {
        if (taps.empty()) return;
        if (samplesPerTap == 0) samplesPerTap = static_cast<int>(samples.size());
        if (static_cast<int>(samples.size()) != samplesPerTap)
            throw InputError(path, "line " + std::to_string(lastRow),
                             "the tap above has " + std::to_string(samples.size()) +
                                 " samples, the first tap " + std::to_string(samplesPerTap) +
                                 "; every tap of a recording has as many");
        Tap& t = taps.back().record.tap;
        t = Tap(static_cast<int>(samples.size()), taxels);
        for (std::size_t s = 0; s < samples.size(); ++s)
            for (int k = 0; k < taxels; ++k)
                t.at(static_cast<int>(s), k) = samples[s][static_cast<std::size_t>(k)];
        samples.clear();
    };
    std::vector<std::string> f;
    while (rows.next(f)) {
        lineNo = rows.line();
        const int set = integer(f[0], "set");
        if (set < 1)
            throw InputError(path, "line " + std::to_string(lineNo) + ", column set",
                             "data set " + f[0] + " is below 1; data sets are numbered from 1");
        const int cls = integer(f[1], "class");
        if (cls < 0 || cls >= classes.classCount())
            throw InputError(path, "line " + std::to_string(lineNo) + ", column class",
                             "class " + f[1] + " is outside 0.." +
                                 std::to_string(classes.classCount() - 1) +
                                 " for this experiment's classes");
        // A class number means an orientation and a position only within its class set: a row
        // naming others was recorded with other classes.
        const double orientation = number(f[2], "orientation_deg");
        const int position = integer(f[3], "position");
        if (orientation != classes.orientationDegOf(cls) || position != classes.positionOf(cls))
            throw InputError(path, "line " + std::to_string(lineNo) + ", column class",
                             "class " + f[1] + " is the " +
                                 ClassSet::orientationName(classes.orientationDegOf(cls)) +
                                 " edge at position " + std::to_string(classes.positionOf(cls)) +
                                 " in these classes, but the row says orientation " + f[2] +
                                 " deg, position " + f[3] +
                                 "; the taps were recorded with other classes: give the "
                                 "experiment they were recorded with");
        const int sample = integer(f[sampleColumn], "sample");
        if (sample == 0) {
            finishTap();
            CollectedTap c;
            c.dataSet = set;
            c.cls = cls;
            c.trueOffset_mm = number(f[4], "true_offset_mm");
            if (std::abs(c.trueOffset_mm) > std::max(bounds.travel_mm.x, bounds.travel_mm.y))
                throw InputError(path, "line " + std::to_string(lineNo) + ", column true_offset_mm",
                                 "an offset of " + f[4] + " mm from the edge is beyond the stage");
            c.record.pose = {number(f[5], "pose_x_mm"), number(f[6], "pose_y_mm")};
            checkPose(c.record.pose, bounds, path, lineNo, f[5], f[6]);
            c.record.startTime_s = number(f[7], "robot_time_s");
            checkTime(c.record.startTime_s, lastTime, path, lineNo, f[7]);
            lastTime = c.record.startTime_s;
            first.assign(f.begin(), f.begin() + perTap);
            firstLine = lineNo;
            if (f[8] != "reflex" && f[8] != "stroke_limit")
                throw InputError(path, "line " + std::to_string(lineNo) + ", column ending",
                                 "'" + f[8] + "' is neither reflex nor stroke_limit");
            c.record.ending = f[8] == "reflex" ? TapEnding::ContactReflex : TapEnding::StrokeLimit;
            if (!earlier) {
                c.record.stopDepth_mm = number(f[9], "stop_depth_mm");
                if (c.record.stopDepth_mm < 0.0 || c.record.stopDepth_mm > 100.0)
                    throw InputError(path,
                                     "line " + std::to_string(lineNo) + ", column stop_depth_mm",
                                     "a stop depth of " + f[9] +
                                         " mm is not an indentation (0 for none, up to the "
                                         "stroke, never over 100 mm)");
            }
            taps.push_back(c);
        } else if (taps.empty() || sample != static_cast<int>(samples.size()) ||
                   taps.back().cls != cls || taps.back().dataSet != set) {
            throw InputError(path, "line " + std::to_string(lineNo) + ", column sample",
                             "sample " + f[sampleColumn] +
                                 " does not continue the tap above it; each tap's samples run 0, "
                                 "1, 2, ... in order");
        } else {
            sameAsFirstRow(f, first, columns, perTap, path, lineNo, firstLine);
        }
        if (bounds.samplesPerTap > 0 && static_cast<int>(samples.size()) >= samplesPerTap)
            throw InputError(path, "line " + std::to_string(lineNo) + ", column sample",
                             "the tap has more than " + std::to_string(samplesPerTap) +
                                 " samples, as many as the run's run.json gives");
        std::vector<double> frame(static_cast<std::size_t>(taxels));
        for (int k = 0; k < taxels; ++k) {
            const std::string& column = header[static_cast<std::size_t>(fixed + k)];
            const double v = number(f[static_cast<std::size_t>(fixed + k)], column);
            if (v < 0.0 || v > 255.0)
                throw InputError(path, "line " + std::to_string(lineNo) + ", column " + column,
                                 "pressure " + f[static_cast<std::size_t>(fixed + k)] +
                                     " is outside the fingertip's 0..255 counts");
            frame[static_cast<std::size_t>(k)] = v;
        }
        samples.push_back(std::move(frame));
        lastRow = lineNo;
    }
    // The last tap: whole, or cut short by a run that stopped while writing it.
    std::string cut;
    if (!taps.empty() && samplesPerTap > 0 && static_cast<int>(samples.size()) < samplesPerTap) {
        const CollectedTap& last = taps.back();
        cut = "the last tap (set " + std::to_string(last.dataSet) + ", class " +
              std::to_string(last.cls) + ") has " + std::to_string(samples.size()) + " of " +
              std::to_string(samplesPerTap) + " samples";
        taps.pop_back();
    } else {
        finishTap();
    }
    if (!rows.cutOff().empty()) cut = (cut.empty() ? std::string() : cut + "; ") + rows.cutOff();
    if (taps.empty()) throw InputError(path, "line 2", "the file holds no whole tap");
    if (!cut.empty()) {
        if (!cutOff)
            throw InputError(path, "the end",
                             cut +
                                 "; the recording was cut short, as by a run stopped while "
                                 "writing");
        *cutOff = cut;
    }
    return taps;
}

}  // namespace activetouch
