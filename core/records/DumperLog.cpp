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

/// Lines of a text file, each refused past kMaxRecordingLineBytes; the last line's lack of a
/// newline is reported through `unterminated`.
class TextLines {
public:
    explicit TextLines(const std::string& path) : path_(path), in_(openRecording(path)) {}
    bool next(std::string& line) {
        if (!std::getline(in_, line)) return false;
        ++number_;
        unterminated_ = in_.eof();
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.size() > kMaxRecordingLineBytes)
            throw InputError(path_, lineName(number_),
                             "the line is longer than " + std::to_string(kMaxRecordingLineBytes) +
                                 " bytes; this is not a skin log");
        return true;
    }
    int number() const { return number_; }
    bool unterminated() const { return unterminated_; }

private:
    std::string path_;
    std::ifstream in_;
    int number_ = 0;
    bool unterminated_ = false;
};

struct FingerBlock {
    const char* name;
    int first;
};
constexpr FingerBlock kFingers[] = {
    {"index", 0}, {"middle", 12}, {"ring", 24}, {"little", 36}, {"thumb", 48}};

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
            const FingerBlock* block = nullptr;
            for (const auto& f : kFingers)
                if (w[1] == f.name) block = &f;
            if (!block)
                throw InputError(path, lineName(at),
                                 "'" + shortened(std::string(w[1]), 40) +
                                     "' is no finger; use index, middle, ring, little or thumb");
            for (int k = 0; k < taxels; ++k) use(k, block->first + k, at);
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

SkinStream readDumperLog(const std::string& path, const TaxelMap& map) {
    const bool folder = fs::is_directory(path);
    const std::string dataPath = folder ? (fs::path(path) / "data.log").string() : path;
    const fs::path infoPath = fs::path(dataPath).parent_path() / "info.log";

    SkinStream s;
    s.source = dataPath;
    s.taxels = static_cast<int>(map.valueOf.size());
    s.stamps = 0;  // unknown until info.log or the first line says
    std::error_code ec;
    if (fs::is_regular_file(infoPath, ec)) {
        TextLines info(infoPath.string());
        std::string line;
        while (info.next(line)) {
            const auto at = line.find("Stamp:");
            if (at == std::string::npos) continue;
            const std::string kind = line.substr(at + 6);
            s.stamps = kind.find("tx+rx") != std::string::npos ? 2 : 1;
        }
    }

    TextLines lines(dataPath);
    std::string line;
    std::int64_t previousCounter = -1;
    double previousTime = -1e300;
    while (lines.next(line)) {
        const int at = lines.number();
        auto w = words(line);
        if (w.empty()) continue;
        if (s.stamps == 0) {
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
        // A frame logged as a list comes in parentheses.
        const std::size_t firstValue = 1 + static_cast<std::size_t>(s.stamps);
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
                dataPath, lineName(at),
                "the frame has " + std::to_string(std::max(values, 0L)) + " values where " +
                    std::to_string(map.valuesPerFrame) + " are expected" +
                    (lines.unterminated() && values < map.valuesPerFrame
                         ? " (the log's last line is cut short: the dumper stopped while "
                           "writing it; remove that line)"
                         : (values < map.valuesPerFrame ? " (a truncated line?)" : "")));
        const double counter = number(w[0], dataPath, at, "counter");
        if (counter != std::floor(counter) || counter < 0 || counter > 9007199254740992.0)
            throw InputError(dataPath, lineName(at) + ", counter",
                             "'" + std::string(w[0]) + "' is not a whole number");
        if (static_cast<std::int64_t>(counter) <= previousCounter)
            throw InputError(dataPath, lineName(at) + ", counter",
                             "counter " + std::string(w[0]) + " after " +
                                 std::to_string(previousCounter) +
                                 ": a dumper's counter rises line by line (are two logs mixed?)");
        if (previousCounter >= 0)
            s.framesMissing += static_cast<std::int64_t>(counter) - previousCounter - 1;
        previousCounter = static_cast<std::int64_t>(counter);
        // With tx and rx both logged, tx (the sender's time) comes first.
        const double time = number(w[1], dataPath, at, "stamp");
        if (s.stamps == 2) number(w[2], dataPath, at, "second stamp");
        if (time < previousTime)
            throw InputError(dataPath, lineName(at) + ", stamp",
                             "the stamp " + std::string(w[1]) + " runs backwards from " +
                                 numberText(previousTime) + "; a log's frames are in time order");
        previousTime = time;
        s.counters.push_back(static_cast<std::uint64_t>(counter));
        s.times_s.push_back(time);
        s.lines.push_back(at);
        for (int k = 0; k < s.taxels; ++k) {
            const int index = map.valueOf[static_cast<std::size_t>(k)];
            const std::string field = "value " + std::to_string(index);
            const double v =
                number(w[firstValue + static_cast<std::size_t>(index)], dataPath, at, field);
            if (v < 0 || v > 255)
                throw InputError(dataPath, lineName(at) + ", " + field,
                                 numberText(v) + " is outside the skin's 0..255");
            s.values.push_back(v);
        }
        // The values the map does not read must still be numbers.
        for (std::size_t i = firstValue; i < w.size(); ++i) {
            double v;
            if (!parseNumber(w[i], v))
                throw InputError(
                    dataPath, lineName(at) + ", value " + std::to_string(i - firstValue),
                    "'" + shortened(std::string(w[i]), 40) + "' is not a finite number");
        }
    }
    if (s.frameCount() == 0) throw InputError(dataPath, "line 1", "the log holds no frames");
    return s;
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
        checkTime(e.time_s, previous < -1e299 ? 0.0 : previous, path, at, "time_s");
        checkPose(e.pose, bounds, path, at, "x_mm", "y_mm");
        previous = e.time_s;
        out.push_back(e);
    }
    if (out.empty()) throw InputError(path, "line 1", "the pose log holds no taps");
    return out;
}

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
