#pragma once
// Real skin recordings in layouts other than YARP's dataDumper (docs/real-fingertips.md): a text
// table of frames, one frame per line or per group of lines, whose layout file says which numbers
// are which finger's taxels, whether readings are inverted (an 8-bit iCub skin reads 255 with no
// pressure and less as it is pressed) and where a time stamp is, if any.
#include <optional>
#include <string>
#include <vector>

#include "core/io/JsonFields.h"

namespace activetouch {

struct FramesLayout {
    std::string source;  ///< the layout file, for messages
    std::string about;   ///< what recordings it reads (free text, with any copyright notice)
    int headerLines = 0;
    int linesPerFrame = 1;
    struct Finger {
        std::string name;
        int line = 1;         ///< within a frame, from 1
        int firstColumn = 1;  ///< from 1, numbers separated by spaces, tabs or commas
        int taxels = 12;
    };
    std::vector<Finger> fingers;
    double fullScale = 255.0;  ///< the largest reading
    bool inverted = false;     ///< pressure = fullScale - reading (else the reading itself)
    struct TimeStamp {
        int line = 1, column = 1;
        double toSeconds = 1.0;
    };
    std::optional<TimeStamp> time;

    int taxelCount() const;  ///< over every finger
};

/// Reads a layout document (docs/real-fingertips.md). Throws InputError naming `source` and the
/// key.
FramesLayout parseFramesLayout(const Json& json, const std::string& source);
FramesLayout loadFramesLayout(const std::string& path);

/// One recording's frames: per frame, every finger's taxels in layout order, as pressure counts
/// (inverted where the layout says so), and the frame's time in seconds where it has one.
struct FramesFile {
    std::string path;
    int frames = 0;
    std::vector<double> pressures;  ///< frames x layout.taxelCount()
    std::vector<double> times_s;    ///< empty without time stamps
    double at(int frame, int taxel, int taxelCount) const {
        return pressures[static_cast<std::size_t>(frame) * static_cast<std::size_t>(taxelCount) +
                         static_cast<std::size_t>(taxel)];
    }
};

/// A file past this many bytes is refused before it is read.
inline constexpr unsigned long long kMaxFramesFileBytes = 1ull << 30;

/// Reads `path` with `layout`. Throws InputError naming the file and line: a line with too few
/// numbers for a finger, a word that is no number, a reading outside 0..fullScale, time going
/// back, or a last frame cut short.
FramesFile readFramesFile(const FramesLayout& layout, const std::string& path);

}  // namespace activetouch
