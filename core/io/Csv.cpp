#include "core/io/Csv.h"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <filesystem>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"
#include "core/io/OutputFile.h"

namespace activetouch {

void writeTapTableHeader(OutputFile& file, const char* const* columns, int count, int taxels) {
    for (int i = 0; i < count; ++i) file.print("%s%s", i ? "," : "", columns[i]);
    for (int k = 0; k < taxels; ++k) file.print(",taxel_%d", k);
    file.put('\n');
    file.flush();
}

std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const auto comma = line.find(',', start);
        out.push_back(
            line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (!out.empty() && !out.back().empty() && out.back().back() == '\r') out.back().pop_back();
    return out;
}

double csvNumber(const std::string& field, const std::string& path, int line,
                 const std::string& column) {
    double v = 0.0;
    const auto res = std::from_chars(field.data(), field.data() + field.size(), v);
    const std::string place = "line " + std::to_string(line) + ", column " + column;
    if (res.ec != std::errc() || res.ptr != field.data() + field.size())
        throw InputError(path, place, "'" + field + "' is not a number");
    if (!std::isfinite(v)) throw InputError(path, place, "'" + field + "' is not a finite number");
    return v;
}

int csvInteger(const std::string& field, const std::string& path, int line,
               const std::string& column) {
    const double v = csvNumber(field, path, line, column);
    if (v != std::floor(v) || std::abs(v) > 1e9)
        throw InputError(
            path, "line " + std::to_string(line) + ", column " + column,
            "'" + field + "' is not a whole number within +-1e9, as the column must be");
    return static_cast<int>(v);
}

void checkPose(Vec2 pose, const RecordingBounds& bounds, const std::string& path, int line,
               const std::string& x, const std::string& y, const std::string& xColumn,
               const std::string& yColumn) {
    constexpr double kSlack_mm = 1e-6;
    const auto inside = [&](double v, double travel) {
        return v >= -kSlack_mm && v <= travel + kSlack_mm;
    };
    if (!inside(pose.x, bounds.travel_mm.x) || !inside(pose.y, bounds.travel_mm.y)) {
        char travel[64];
        std::snprintf(travel, sizeof travel, "0..%g, 0..%g mm", bounds.travel_mm.x,
                      bounds.travel_mm.y);
        throw InputError(path,
                         "line " + std::to_string(line) + ", column " +
                             (inside(pose.x, bounds.travel_mm.x) ? yColumn : xColumn),
                         "the pose (" + x + ", " + y + ") mm lies outside the stage travel (" +
                             travel + "); no tap was taken there");
    }
}

void checkTaxelCount(int taxels, const RecordingBounds& bounds, const std::string& path) {
    if (bounds.taxels <= 0 || taxels == bounds.taxels) return;
    throw InputError(path, "line 1",
                     "the recording has " + std::to_string(taxels) + " taxel columns, but " +
                         (bounds.taxelsFrom.empty() ? std::string("its fingertip")
                                                    : bounds.taxelsFrom) +
                         " has " + std::to_string(bounds.taxels) +
                         " taxels; it was recorded with another fingertip, or damaged");
}

void checkTime(double time, double previous, const std::string& path, int line,
               const std::string& field, const std::string& column) {
    const std::string place = "line " + std::to_string(line) + ", column " + column;
    if (time < 0.0)
        throw InputError(path, place, "robot time " + field + " s is negative");
    if (time < previous)
        throw InputError(path, place,
                         "robot time " + field + " s is earlier than the tap before it; taps are "
                                                 "recorded in the order they were taken");
}

void sameAsFirstRow(const std::vector<std::string>& row, const std::vector<std::string>& first,
                    const char* const* columns, int count, const std::string& path, int line,
                    int firstLine) {
    for (int i = 0; i < count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (row[k] != first[k])
            throw InputError(path, "line " + std::to_string(line) + ", column " + columns[i],
                             "'" + row[k] + "' differs from the tap's first row (line " +
                                 std::to_string(firstLine) + ": '" + first[k] +
                                 "'); a tap's own columns are the same on every one of its rows");
    }
}

std::ifstream openRecording(const std::string& path) {
    std::ifstream in = openInputFile(path);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > kMaxRecordingBytes)
        throw InputError(path, "",
                         "the recording is " + std::to_string(size >> 20) +
                             " MiB, over the " + std::to_string(kMaxRecordingBytes >> 20) +
                             " MiB a recording may have (about 200,000 taps); split the run");
    return in;
}

RecordingRows::RecordingRows(std::istream& in, const std::string& path)
    : lines_(in, path, kMaxRecordingLineBytes,
             "a recording's rows are well under one, so this is not a recording the workbench "
             "wrote"),
      path_(path) {
    std::string line;
    if (!lines_.next(line))
        throw InputError(path_, "line 1", "the file is empty; expected a header row");
    header_ = splitCsvLine(line);
}

bool RecordingRows::next(std::vector<std::string>& fields) {
    std::string line;
    while (lines_.next(line)) {
        line_ = lines_.number();
        if (line.empty()) continue;
        if (brokenAt_)
            throw InputError(path_, "line " + std::to_string(brokenAt_),
                             broken_ + "; only the file's last line may be cut short");
        fields = splitCsvLine(line);
        if (fields.size() == header_.size()) return true;
        brokenAt_ = line_;
        broken_ = "has " + std::to_string(fields.size()) + " fields, the header has " +
                  std::to_string(header_.size());
    }
    return false;
}

std::string RecordingRows::cutOff() const {
    if (!brokenAt_) return {};
    return "line " + std::to_string(brokenAt_) + " is cut off (" + broken_ + ")";
}

}  // namespace activetouch
