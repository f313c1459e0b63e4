#include "core/records/DumperLog.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/io/InputFile.h"
#include "core/io/OutputFile.h"

namespace activetouch {
namespace {

namespace fs = std::filesystem;

std::string lineName(int line) {
    return "line " + std::to_string(line);
}

/// The whitespace-separated words of `line`, without a comment.
std::vector<std::string_view> words(std::string_view line) {
    if (const auto hash = line.find('#'); hash != std::string_view::npos)
        line = line.substr(0, hash);
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        const std::size_t start = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

bool parseNumber(std::string_view text, double& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

double number(std::string_view text, const std::string& path, int line, const std::string& field) {
    double v = 0.0;
    if (!parseNumber(text, v))
        throw InputError(path, lineName(line) + ", " + field,
                         "'" + shortened(std::string(text), 40) +
                             "' is not a finite number; a line holds numbers only");
    return v;
}

int wholeNumber(std::string_view text, const std::string& path, int line, const std::string& field,
                int most) {
    const double v = number(text, path, line, field);
    if (v != std::floor(v) || v < 0 || v > most)
        throw InputError(
            path, lineName(line) + ", " + field,
            "'" + std::string(text) + "' is not a whole number within 0.." + std::to_string(most));
    return static_cast<int>(v);
}

/// Lines of a text file, each refused past kMaxRecordingLineBytes before more of it is held.
class TextLines {
public:
    explicit TextLines(const std::string& path)
        : in_(openRecording(path)),
          lines_(in_, path, kMaxRecordingLineBytes,
                 "a skin log, pose log or taxel map has short lines, so this is not one") {}
    bool next(std::string& line) { return lines_.next(line); }
    int number() const { return lines_.number(); }
    bool unterminated() const { return lines_.unterminated(); }

private:
    std::ifstream in_;
    BoundedLines lines_;
};

struct FingerBlock {
    const char* name;
    int first;
};
constexpr FingerBlock kFingers[] = {
    {"index", 0}, {"middle", 12}, {"ring", 24}, {"little", 36}, {"thumb", 48}};

/// The first of the 12 values `name`'s fingertip has in an iCub hand's skin vector.
int fingerBlock(std::string_view name, const std::string& path, int at) {
    for (const auto& f : kFingers)
        if (name == f.name) return f.first;
    throw InputError(path, lineName(at),
                     "'" + shortened(std::string(name), 40) +
                         "' is no finger; use index, middle, ring, little or thumb");
}

}  // namespace

TaxelMap readTaxelMap(const std::string& path, int taxels) {
    TaxelMap map;
    TextLines lines(path);
    std::string line;
    std::vector<int> usedBy;  // value index -> taxel + 1
    auto use = [&](int taxel, int value, int at) {
        if (value >= map.valuesPerFrame)
            throw InputError(path, lineName(at),
                             "value " + std::to_string(value) + " lies past the frame's " +
                                 std::to_string(map.valuesPerFrame) +
                                 " values (they are numbered from 0)");
        if (usedBy[static_cast<std::size_t>(value)] != 0)
            throw InputError(path, lineName(at),
                             "value " + std::to_string(value) + " is already taxel " +
                                 std::to_string(usedBy[static_cast<std::size_t>(value)] - 1) +
                                 "'s; each taxel reads a value of its own");
        usedBy[static_cast<std::size_t>(value)] = taxel + 1;
        map.valueOf.push_back(value);
    };
    while (lines.next(line)) {
        const auto w = words(line);
        if (w.empty()) continue;
        const int at = lines.number();
        if (map.valuesPerFrame == 0) {
            if (w.size() != 2 || w[0] != "values_per_frame")
                throw InputError(path, lineName(at),
                                 "a taxel map starts with 'values_per_frame N' (192 for an iCub "
                                 "hand's skin port)");
            map.valuesPerFrame = wholeNumber(w[1], path, at, "values_per_frame", kMaxTaxels);
            if (map.valuesPerFrame < taxels)
                throw InputError(path, lineName(at),
                                 "a frame of " + std::to_string(map.valuesPerFrame) +
                                     " values cannot hold the fingertip's " +
                                     std::to_string(taxels) + " taxels");
            usedBy.assign(static_cast<std::size_t>(map.valuesPerFrame), 0);
            continue;
        }
        if (w[0] == "finger" && w.size() == 2) {
            if (!map.valueOf.empty())
                throw InputError(path, lineName(at),
                                 "'finger' names all the fingertip's taxels at once; give it "
                                 "alone, or list every taxel");
            const int first = fingerBlock(w[1], path, at);
            for (int k = 0; k < taxels; ++k) use(k, first + k, at);
            continue;
        }
        if (w.size() != 4 || w[0] != "taxel" || w[2] != "value")
            throw InputError(
                path, lineName(at),
                "expected 'taxel K value V' (or 'finger NAME'); got '" + shortened(line, 60) + "'");
        const int taxel = wholeNumber(w[1], path, at, "taxel", kMaxTaxels);
        const int expected = static_cast<int>(map.valueOf.size());
        if (taxel != expected)
            throw InputError(path, lineName(at),
                             "taxel " + std::to_string(taxel) + " where taxel " +
                                 std::to_string(expected) +
                                 " comes next: list the fingertip's taxels in order 0.." +
                                 std::to_string(taxels - 1) + ", each once (is the map shuffled?)");
        if (taxel >= taxels)
            throw InputError(path, lineName(at),
                             "the fingertip has " + std::to_string(taxels) + " taxels (0.." +
                                 std::to_string(taxels - 1) + "); taxel " + std::to_string(taxel) +
                                 " is not one of them");
        use(taxel, wholeNumber(w[3], path, at, "value", kMaxTaxels), at);
    }
    if (map.valuesPerFrame == 0)
        throw InputError(path, "line 1",
                         "the taxel map is empty; it starts with 'values_per_frame N'");
    if (static_cast<int>(map.valueOf.size()) != taxels)
        throw InputError(path, lineName(lines.number()),
                         "the map ends after " + std::to_string(map.valueOf.size()) +
                             " taxels; the fingertip has " + std::to_string(taxels) +
                             ": list every one");
    return map;
}

std::string taxelMapText(const TaxelMap& map) {
    std::string out = "values_per_frame " + std::to_string(map.valuesPerFrame) + "\n";
    for (std::size_t k = 0; k < map.valueOf.size(); ++k)
        out += "taxel " + std::to_string(k) + " value " + std::to_string(map.valueOf[k]) + "\n";
    return out;
}

namespace {

/// Stamps per line as info.log's "Stamp:" line says (2 for tx+rx), or 0 if it does not say.
int stampsFromInfo(const fs::path& infoPath) {
    int stamps = 0;
    std::error_code ec;
    if (!fs::is_regular_file(infoPath, ec)) return stamps;
    TextLines info(infoPath.string());
    std::string line;
    while (info.next(line)) {
        const auto at = line.find("Stamp:");
        if (at == std::string::npos) continue;
        stamps = line.find("tx+rx", at) != std::string::npos ? 2 : 1;
    }
    return stamps;
}

/// The frame's values in `w` after the counter and stamps, without a list's parentheses;
/// refuses a frame of another size than the map's.
void checkFrameWidth(std::vector<std::string_view>& w, std::size_t firstValue, const TaxelMap& map,
                     const std::string& path, int at, bool lastLineCut) {
    // A frame logged as a list comes in parentheses.
    if (w.size() > firstValue && !w[firstValue].empty() && w[firstValue].front() == '(' &&
        !w.back().empty() && w.back().back() == ')') {
        w[firstValue].remove_prefix(1);
        w.back().remove_suffix(1);
        if (w[firstValue].empty()) w.erase(w.begin() + static_cast<long>(firstValue));
        if (!w.empty() && w.back().empty()) w.pop_back();
    }
    const long values = static_cast<long>(w.size()) - static_cast<long>(firstValue);
    if (values != map.valuesPerFrame)
        throw InputError(
            path, lineName(at),
            "the frame has " + std::to_string(std::max(values, 0L)) + " values where " +
                std::to_string(map.valuesPerFrame) + " are expected" +
                (lastLineCut && values < map.valuesPerFrame
                     ? " (the log's last line is cut short: the dumper stopped while "
                       "writing it; remove that line)"
                     : (values < map.valuesPerFrame ? " (a truncated line?)" : "")));
}

/// The fastest a skin streams: a counter may skip frames, but never more than this many a
/// second of its stamps (with a floor of as many for stamps that do not advance).
constexpr double kMaxFramesPerSecond = 1000.0;

/// Reads the counter and the stamp, refusing a counter that falls, jumps further than the
/// stamps allow, or a stamp that runs backwards.
void readCounterAndStamp(const std::vector<std::string_view>& w, SkinStream& s,
                         const std::string& path, int at) {
    const double counter = number(w[0], path, at, "counter");
    if (counter != std::floor(counter) || counter < 0 || counter > 9007199254740992.0)
        throw InputError(path, lineName(at) + ", counter",
                         "'" + std::string(w[0]) + "' is not a whole number");
    const double time = number(w[1], path, at, "stamp");  // tx, the sender's time, comes first
    if (s.stamps == 2) number(w[2], path, at, "second stamp");
    if (!s.counters.empty()) {
        const double previous = static_cast<double>(s.counters.back());
        const double lastTime = s.times_s.back();
        if (counter <= previous)
            throw InputError(path, lineName(at) + ", counter",
                             "counter " + std::string(w[0]) + " after " + numberText(previous) +
                                 ": a dumper's counter rises line by line (are two logs mixed?)");
        if (time < lastTime)
            throw InputError(path, lineName(at) + ", stamp",
                             "the stamp " + std::string(w[1]) + " runs backwards from " +
                                 numberText(lastTime) + "; a log's frames are in time order");
        const double jump = counter - previous;
        const double most = kMaxFramesPerSecond * std::max(1.0, time - lastTime);
        if (jump > most)
            throw InputError(path, lineName(at) + ", counter",
                             "counter " + std::string(w[0]) + " after " + numberText(previous) +
                                 " skips " + numberText(jump - 1) + " frames while the stamp " +
                                 "advances " + numberText(time - lastTime) +
                                 " s; a skin streams at most " + numberText(kMaxFramesPerSecond) +
                                 " frames a second, so the log is damaged or two are mixed");
        s.framesMissing += static_cast<std::int64_t>(jump) - 1;
    }
    s.counters.push_back(static_cast<std::uint64_t>(counter));
    s.times_s.push_back(time);
    s.lines.push_back(at);
}

/// Reads the frame's values: the map's taxels into `s`, every value's range kept.
void readValues(const std::vector<std::string_view>& w, std::size_t firstValue,
                const TaxelMap& map, SkinStream& s, const std::string& path, int at) {
    for (int k = 0; k < s.taxels; ++k) {
        const int index = map.valueOf[static_cast<std::size_t>(k)];
        const std::string field = "value " + std::to_string(index);
        const double v = number(w[firstValue + static_cast<std::size_t>(index)], path, at, field);
        if (v < 0 || v > 255)
            throw InputError(path, lineName(at) + ", " + field,
                             numberText(v) + " is outside the skin's 0..255");
        s.values.push_back(v);
    }
    // The values the map does not read must still be numbers; each one's range is kept.
    const bool first = s.valueLow.empty();
    if (first) {
        s.valueLow.assign(static_cast<std::size_t>(map.valuesPerFrame), 1e300);
        s.valueHigh.assign(static_cast<std::size_t>(map.valuesPerFrame), -1e300);
    }
    for (std::size_t i = firstValue; i < w.size(); ++i) {
        double v;
        if (!parseNumber(w[i], v))
            throw InputError(path, lineName(at) + ", value " + std::to_string(i - firstValue),
                             "'" + shortened(std::string(w[i]), 40) + "' is not a finite number");
        const std::size_t j = i - firstValue;
        s.valueLow[j] = std::min(s.valueLow[j], v);
        s.valueHigh[j] = std::max(s.valueHigh[j], v);
    }
}

}  // namespace

SkinStream readDumperLog(const std::string& path, const TaxelMap& map) {
    const bool folder = fs::is_directory(path);
    const std::string dataPath = folder ? (fs::path(path) / "data.log").string() : path;
    SkinStream s;
    s.source = dataPath;
    s.taxels = static_cast<int>(map.valueOf.size());
    s.stamps = stampsFromInfo(fs::path(dataPath).parent_path() / "info.log");
    TextLines lines(dataPath);
    std::string line;
    while (lines.next(line)) {
        const int at = lines.number();
        auto w = words(line);
        if (w.empty()) continue;
        if (s.stamps == 0) {  // unknown until info.log or the first line says
            const long extra = static_cast<long>(w.size()) - 1 - map.valuesPerFrame;
            if (extra != 1 && extra != 2)
                throw InputError(dataPath, lineName(at),
                                 "the line has " + std::to_string(w.size()) +
                                     " fields; a dumper line is a counter, one or two stamps and "
                                     "the frame's " +
                                     std::to_string(map.valuesPerFrame) +
                                     " values (the taxel map's values_per_frame)");
            s.stamps = static_cast<int>(extra);
        }
        const std::size_t firstValue = 1 + static_cast<std::size_t>(s.stamps);
        checkFrameWidth(w, firstValue, map, dataPath, at, lines.unterminated());
        readCounterAndStamp(w, s, dataPath, at);
        readValues(w, firstValue, map, s, dataPath, at);
    }
    if (s.frameCount() == 0) throw InputError(dataPath, "line 1", "the log holds no frames");
    return s;
}

void checkMapReadsTheTouch(const SkinStream& s, const TaxelMap& map, const std::string& mapPath) {
    auto range = [&](std::size_t j) { return s.valueHigh[j] - s.valueLow[j]; };
    double mapped = 0.0;
    std::vector<bool> isMapped(s.valueLow.size(), false);
    for (const int v : map.valueOf) {
        isMapped[static_cast<std::size_t>(v)] = true;
        mapped = std::max(mapped, range(static_cast<std::size_t>(v)));
    }
    double other = 0.0;
    std::size_t where = 0;
    for (std::size_t j = 0; j < isMapped.size(); ++j)
        if (!isMapped[j] && range(j) > other) {
            other = range(j);
            where = j;
        }
    if (mapped >= kMinTouchRange_counts || other < kMinTouchRange_counts) return;
    const auto finger = std::find_if(std::begin(kFingers), std::end(kFingers), [&](const auto& f) {
        return where >= static_cast<std::size_t>(f.first) &&
               where < static_cast<std::size_t>(f.first) + 12;
    });
    throw InputError(mapPath, "",
                     "the taxels this map reads never vary by more than " + numberText(mapped) +
                         " counts in " + s.source + ", while value " + std::to_string(where) +
                         (map.valuesPerFrame == 192 && finger != std::end(kFingers)
                              ? std::string(" (the ") + finger->name + " finger's)"
                              : std::string()) +
                         " varies by " + numberText(other) +
                         ": the map names another fingertip than the one that touched; give the "
                         "map of that fingertip");
}

std::vector<PoseLogEntry> readPoseLog(const std::string& path, const RecordingBounds& bounds) {
    std::vector<PoseLogEntry> out;
    TextLines lines(path);
    std::string line;
    double previous = -1e300;
    while (lines.next(line)) {
        const auto w = words(line);
        if (w.empty()) continue;
        const int at = lines.number();
        if (w.size() != 3 && w.size() != 4)
            throw InputError(path, lineName(at),
                             "a pose line is 'time_s x_mm y_mm' (or 'counter time_s x_mm y_mm'); "
                             "this one has " +
                                 std::to_string(w.size()) + " fields" +
                                 (lines.unterminated() ? " (cut short?)" : ""));
        const std::size_t o = w.size() - 3;
        PoseLogEntry e;
        e.line = at;
        e.time_s = number(w[o], path, at, "time_s");
        e.pose = {number(w[o + 1], path, at, "x_mm"), number(w[o + 2], path, at, "y_mm")};
        checkTime(e.time_s, previous < -1e299 ? 0.0 : previous, path, at, std::string(w[o]),
                  "time_s");
        checkPose(e.pose, bounds, path, at, std::string(w[o + 1]), std::string(w[o + 2]), "x_mm",
                  "y_mm");
        previous = e.time_s;
        out.push_back(e);
    }
    if (out.empty()) throw InputError(path, "line 1", "the pose log holds no taps");
    return out;
}

void writeDumperLog(const std::string& folder, const std::vector<TapRecord>& taps,
                    const TaxelMap& map, double sampleRate_hz) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    const double period = 1.0 / sampleRate_hz;
    {
        OutputFile info((fs::path(folder) / "info.log").string());
        info.print("Type: Bottle;\nStamp: tx;\n");
        info.close();
    }
    OutputFile data((fs::path(folder) / "data.log").string());
    OutputFile poses((fs::path(folder) / "poses.log").string());
    poses.print("# time_s x_mm y_mm: where and when each tap began\n");
    std::vector<double> frame(static_cast<std::size_t>(map.valuesPerFrame), 0.0);
    std::uint64_t counter = 0;
    auto put = [&](double time, const double* taxels) {
        std::fill(frame.begin(), frame.end(), 0.0);
        if (taxels)
            for (std::size_t k = 0; k < map.valueOf.size(); ++k)
                frame[static_cast<std::size_t>(map.valueOf[k])] = taxels[k];
        data.print("%llu %.6f", static_cast<unsigned long long>(counter++), time);
        for (double v : frame) data.print(" %.17g", v);
        data.put('\n');
    };
    for (std::size_t i = 0; i < taps.size(); ++i) {
        const TapRecord& r = taps[i];
        poses.print("%.17g %.17g %.17g\n", r.startTime_s, r.pose.x, r.pose.y);
        const int T = r.tap.sampleCount();
        for (int t = 0; t < T; ++t) put(r.startTime_s + t * period, r.tap.frame(t));
        // Resting frames until the next tap begins.
        const double next =
            i + 1 < taps.size() ? taps[i + 1].startTime_s : r.startTime_s + T * period;
        for (int t = T;; ++t) {
            const double time = r.startTime_s + t * period;
            if (time >= next - 0.5 * period) break;
            put(time, nullptr);
        }
    }
    data.close();
    poses.close();
}

}  // namespace activetouch
