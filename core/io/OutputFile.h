#pragma once
// A file the project writes: opened truncated, written through printf-style calls and flushed
// when the caller says. A failed write (a full disk, a drive gone) is never silent: the next
// flush or close throws a WriteError naming the file and the system's reason, so a run stops
// instead of recording less than it reports. What was flushed before stays in the file.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace activetouch {

/// A file that could not be written whole. Not bad input: the run that wrote it failed, and what
/// it wrote before stays in the file.
class WriteError : public std::runtime_error {
public:
    /// `reason`: the system's, e.g. "No space left on device"; `advice`: what to do.
    WriteError(std::string path, std::string reason, const std::string& advice)
        : std::runtime_error(path + ": cannot write the file (" + reason + "); " + advice),
          path_(std::move(path)),
          reason_(std::move(reason)) {}
    const std::string& path() const { return path_; }
    const std::string& reason() const { return reason_; }

private:
    std::string path_, reason_;
};

class OutputFile {
public:
    /// Opens (truncating) `path`; throws InputError if it cannot be created.
    explicit OutputFile(std::string path);
    /// Closes the file; a failure here is not reported (call close() to have it checked).
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void print(const char* format, ...) __attribute__((format(printf, 2, 3)));
    void put(char c);
    /// Hands what was written to the system; throws WriteError if any write so far failed.
    void flush();
    /// Flushes and closes; throws WriteError if any write failed. Closing again does nothing;
    /// writes after closing fail.
    void close();
    const std::string& path() const { return path_; }

private:
    void noteFailure();
    [[noreturn]] void raise();

    std::FILE* file_ = nullptr;
    std::string path_;
    int error_ = 0;  ///< errno of the first failed write, 0 while none failed
};

}  // namespace activetouch
