#pragma once
// Opening and reading a file the user named, the one way every reader does it: a missing file, a
// folder, a pipe, a device or an unreadable file is an InputError that says which and what to do,
// before anything tries to read it; a whole file is read only up to a bound, and lines are read
// by a reader that never holds more than its bound of one line.
#include <cstddef>
#include <fstream>
#include <istream>
#include <string>

namespace activetouch {

/// `path` opened for reading. Throws InputError naming `path` if it does not exist, is a folder,
/// is no regular file (a device, a pipe or a socket, which could block or never end) or cannot
/// be read.
std::ifstream openInputFile(const std::string& path, std::ios::openmode mode = std::ios::in);

/// The whole of the file at `path`, opened as openInputFile does; refused (InputError naming the
/// file and `whatItIs`, e.g. "a YARP conf file") past `maxBytes`, having read at most one chunk
/// more than that.
std::string readBoundedFile(const std::string& path, std::size_t maxBytes,
                            const std::string& whatItIs);

/// The lines of a stream, each without its newline (and a trailing '\r'), read in chunks: a line
/// longer than `maxLine` bytes is refused (InputError naming the file and the line) before more
/// than `maxLine` plus one chunk is held, however long the line.
class BoundedLines {
public:
    /// `whatItIs` ends the refusal of a long line: "this is not a skin log".
    BoundedLines(std::istream& in, std::string path, std::size_t maxLine, std::string whatItIs);
    /// The next line, or false at the end of the stream.
    bool next(std::string& line);
    /// The number of the line `next` gave last (from 1).
    int number() const { return number_; }
    /// Whether that line was the last and had no newline (a file cut while it was written).
    bool unterminated() const { return unterminated_; }

    /// Bytes read from the stream at a time.
    static constexpr std::size_t kChunkBytes = 1u << 16;

private:
    std::istream& in_;
    std::string path_, whatItIs_;
    std::size_t maxLine_;
    std::string buffer_;     ///< read ahead of the lines given so far
    std::size_t start_ = 0;  ///< where the next line begins in buffer_
    int number_ = 0;
    bool unterminated_ = false;
};

}  // namespace activetouch
