#include "core/records/FramesTable.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/common/InputError.h"
#include "core/common/Limits.h"
#include "core/common/NumberText.h"
#include "core/io/InputFile.h"

namespace activetouch {

int FramesLayout::taxelCount() const {
    int n = 0;
    for (const Finger& f : fingers) n += f.taxels;
    return n;
}

namespace {

FramesLayout::Finger parseFinger(const JsonFields& f, int linesPerFrame) {
    f.rejectUnknownKeys({"name", "line", "first_column", "taxels"});
    FramesLayout::Finger finger;
    finger.name = f.text("name");
    finger.line = f.integer("line", 1, linesPerFrame);
    finger.firstColumn = f.integer("first_column", 1, 100000, 1);
    finger.taxels = f.integer("taxels", 1, kMaxTaxels, 12);
    return finger;
}

/// The numbers of one line, split at spaces, tabs and commas; a word that is no number is refused
/// naming the line and the column.
std::vector<double> numbersOf(const std::string& line, const std::string& path, int number) {
    std::vector<double> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',')) ++i;
        if (i >= line.size()) break;
        std::size_t end = i;
        while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != ',')
            ++end;
        const std::string word = line.substr(i, end - i);
        char* stop = nullptr;
        errno = 0;
        const double v = std::strtod(word.c_str(), &stop);
        if (stop != word.c_str() + word.size() || errno == ERANGE || !std::isfinite(v))
            throw InputError(path, "line " + std::to_string(number),
                             "column " + std::to_string(out.size() + 1) + " ('" +
                                 shortened(word, 40) +
                                 "') is not a number; check that the layout fits this file");
        out.push_back(v);
        i = end;
    }
    return out;
}

}  // namespace

FramesLayout parseFramesLayout(const Json& json, const std::string& source) {
    const JsonFields f(json, source, "");
    f.rejectUnknownKeys(
        {"layout", "about", "header_lines", "lines_per_frame", "fingers", "reading", "time"});
    if (f.text("layout") != "frames table")
        f.fail("layout", "a frames layout says \"layout\": \"frames table\"");
    FramesLayout l;
    l.source = source;
    l.about = f.text("about", "");
    l.headerLines = f.integer("header_lines", 0, 1000000, 0);
    l.linesPerFrame = f.integer("lines_per_frame", 1, 10000, 1);
    if (!f.has("fingers") || !f.raw("fingers").is_array() || f.raw("fingers").empty())
        f.fail("fingers",
               "list the fingers: each a name, the frame's line and first column of its "
               "taxels, and how many");
    for (std::size_t i = 0; i < f.raw("fingers").size(); ++i) {
        const JsonFields finger(f.raw("fingers")[i], source, "/fingers/" + std::to_string(i));
        l.fingers.push_back(parseFinger(finger, l.linesPerFrame));
        for (std::size_t j = 0; j + 1 < l.fingers.size(); ++j)
            if (l.fingers[j].name == l.fingers.back().name)
                finger.fail("name", "a second finger named '" + l.fingers.back().name + "'");
    }
    if (l.taxelCount() > kMaxTaxels)
        f.fail("fingers", "more than " + std::to_string(kMaxTaxels) + " taxels in all");
    const JsonFields reading = f.object("reading");
    reading.rejectUnknownKeys({"full_scale", "inverted"});
    l.fullScale = reading.number("full_scale", 1.0, 1e9, 255.0);
    l.inverted = reading.flag("inverted", false);
    if (f.has("time")) {
        const JsonFields t = f.object("time");
        t.rejectUnknownKeys({"line", "column", "unit"});
        const std::string unit = t.text("unit", "s");
        const double scale = unit == "s" ? 1.0 : unit == "ms" ? 1e-3 : unit == "us" ? 1e-6 : -1.0;
        if (scale < 0) t.fail("unit", "a time unit is s, ms or us, not '" + unit + "'");
        l.time = FramesLayout::TimeStamp{t.integer("line", 1, l.linesPerFrame),
                                         t.integer("column", 1, 100000), scale};
    }
    return l;
}

FramesLayout loadFramesLayout(const std::string& path) {
    return parseFramesLayout(readJsonFile(path), path);
}

namespace {

/// Reads a frames table line by line: which line of a frame each is, and what it holds.
class FrameReader {
public:
    FrameReader(const FramesLayout& layout, const std::string& path)
        : layout_(layout), path_(path), taxels_(layout.taxelCount()) {
        out_.path = path;
    }

    void take(const std::string& line, int number) {
        const bool blank = line.find_first_not_of(" \t\r,") == std::string::npos;
        if (blank && inFrame_ == 0) return;  // blank lines between frames (or at the end)
        if (inFrame_ == 0) {
            frameStart_ = number;
            out_.pressures.resize(out_.pressures.size() + static_cast<std::size_t>(taxels_));
        }
        ++inFrame_;
        number_ = number;
        const std::vector<double> values = numbersOf(line, path_, number);
        int offset = 0;
        for (const FramesLayout::Finger& finger : layout_.fingers) {
            if (finger.line == inFrame_) readFinger(finger, values, offset);
            offset += finger.taxels;
        }
        if (layout_.time && layout_.time->line == inFrame_) readTime(values);
        if (inFrame_ == layout_.linesPerFrame) {
            inFrame_ = 0;
            ++out_.frames;
        }
    }

    FramesFile finish() {
        if (inFrame_ != 0)
            throw InputError(path_, "line " + std::to_string(frameStart_),
                             "the last frame has " + std::to_string(inFrame_) + " of its " +
                                 std::to_string(layout_.linesPerFrame) +
                                 " lines: the file is cut short, or the layout's lines_per_frame "
                                 "does not fit it");
        if (out_.frames == 0)
            throw InputError(path_, "",
                             "holds no frame after its " + std::to_string(layout_.headerLines) +
                                 " header line(s)");
        return std::move(out_);
    }

private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(path_, "line " + std::to_string(number_), problem);
    }

    void readFinger(const FramesLayout::Finger& finger, const std::vector<double>& values,
                    int offset) {
        const auto last = static_cast<std::size_t>(finger.firstColumn + finger.taxels - 1);
        if (values.size() < last)
            fail("the " + finger.name + " finger's taxels are columns " +
                 std::to_string(finger.firstColumn) + ".." + std::to_string(last) +
                 " of the frame's line " + std::to_string(finger.line) + ", but it has " +
                 std::to_string(values.size()) + " numbers; check the layout (" + layout_.source +
                 ")");
        double* frame = out_.pressures.data() + out_.pressures.size() -
                        static_cast<std::size_t>(taxels_) + offset;
        for (int k = 0; k < finger.taxels; ++k) {
            const double v = values[static_cast<std::size_t>(finger.firstColumn - 1 + k)];
            if (v < 0.0 || v > layout_.fullScale)
                fail("the " + finger.name + " finger's taxel " + std::to_string(k) + " reads " +
                     numberText(v) + ", outside 0.." + numberText(layout_.fullScale) +
                     "; check the layout's full scale (" + layout_.source + ")");
            frame[k] = layout_.inverted ? layout_.fullScale - v : v;
        }
    }

    void readTime(const std::vector<double>& values) {
        const auto column = static_cast<std::size_t>(layout_.time->column);
        if (values.size() < column)
            fail("the time stamp is column " + std::to_string(column) + ", but the line has " +
                 std::to_string(values.size()) + " numbers; check the layout (" + layout_.source +
                 ")");
        const double t = values[column - 1] * layout_.time->toSeconds;
        if (!out_.times_s.empty() && t < out_.times_s.back())
            fail("time goes back (" + numberText(t) + " s after " +
                 numberText(out_.times_s.back()) + " s)");
        out_.times_s.push_back(t);
    }

    const FramesLayout& layout_;
    std::string path_;
    int taxels_ = 0;
    FramesFile out_;
    int inFrame_ = 0, frameStart_ = 0, number_ = 0;
};

}  // namespace

FramesFile readFramesFile(const FramesLayout& layout, const std::string& path) {
    std::ifstream in = openInputFile(path);
    BoundedLines lines(in, path, 1u << 20, "this is not a frames table");
    FrameReader reader(layout, path);
    std::string line;
    while (lines.next(line))
        if (lines.number() > layout.headerLines) reader.take(line, lines.number());
    return reader.finish();
}

}  // namespace activetouch
