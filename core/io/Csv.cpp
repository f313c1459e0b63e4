#include "core/io/Csv.h"

#include <charconv>
#include <cmath>

#include "core/common/InputError.h"
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

RecordingRows::RecordingRows(std::istream& in, const std::string& path) : in_(in), path_(path) {
    std::string line;
    if (!std::getline(in_, line))
        throw InputError(path_, "line 1", "the file is empty; expected a header row");
    header_ = splitCsvLine(line);
}

bool RecordingRows::next(std::vector<std::string>& fields) {
    std::string line;
    while (std::getline(in_, line)) {
        ++line_;
        if (line.empty() || line == "\r") continue;
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
