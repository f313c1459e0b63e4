#include "core/io/OutputFile.h"

#include <cerrno>
#include <cstdarg>
#include <cstring>

#include "core/common/InputError.h"

namespace activetouch {

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
    file_ = std::fopen(path_.c_str(), "w");
    if (!file_)
        throw InputError(path_, "",
                         std::string("cannot create the file (") + std::strerror(errno) +
                             "); check the output folder exists and is writable");
}

OutputFile::~OutputFile() {
    if (file_) std::fclose(file_);
}

void OutputFile::noteFailure() {
    if (error_ == 0) error_ = errno != 0 ? errno : EIO;
}

void OutputFile::raise() {
    throw WriteError(path_, std::strerror(error_),
                     "free space on its disk or choose another output folder, and run again "
                     "(what was written before stays in the file)");
}

void OutputFile::print(const char* format, ...) {
    if (!file_) {
        error_ = error_ ? error_ : EBADF;
        return;
    }
    std::va_list args;
    va_start(args, format);
    errno = 0;
    const int written = std::vfprintf(file_, format, args);
    va_end(args);
    if (written < 0) noteFailure();
}

void OutputFile::put(char c) {
    if (!file_) {
        error_ = error_ ? error_ : EBADF;
        return;
    }
    errno = 0;
    if (std::fputc(c, file_) == EOF) noteFailure();
}

void OutputFile::flush() {
    if (file_) {
        errno = 0;
        if (std::fflush(file_) != 0 || std::ferror(file_)) noteFailure();
    }
    if (error_) raise();
}

void OutputFile::close() {
    if (!file_) return;  // closed before: whatever failed was reported then
    errno = 0;
    if (std::fflush(file_) != 0 || std::ferror(file_)) noteFailure();
    errno = 0;
    if (std::fclose(file_) != 0) noteFailure();
    file_ = nullptr;
    if (error_) raise();
}

}  // namespace activetouch
