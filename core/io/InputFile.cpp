#include "core/io/InputFile.h"

#include <filesystem>
#include <system_error>

#include "core/common/InputError.h"

namespace activetouch {
namespace {

std::string sizeText(std::size_t bytes) {
    if (bytes >= (1u << 20)) return std::to_string(bytes >> 20) + " MiB";
    if (bytes >= (1u << 10)) return std::to_string(bytes >> 10) + " KiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::ifstream openInputFile(const std::string& path, std::ios::openmode mode) {
    if (path.empty()) throw InputError("(an empty path)", "", "no file was named; give a path");
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (std::filesystem::is_directory(status))
        throw InputError(path, "", "this is a folder, not a file; give the path of a file in it");
    // A pipe with no writer would block the open forever, a device never end: only regular
    // files are read.
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw InputError(path, "",
                         "this is not a regular file (a device, a pipe or a socket); give the "
                         "path of a file");
    std::ifstream in(path, mode);
    if (!in) {
        const bool exists = std::filesystem::exists(status);
        throw InputError(path, "",
                         exists ? "cannot read the file; check its permissions"
                                : "no such file; check the path");
    }
    return in;
}

std::string readBoundedFile(const std::string& path, std::size_t maxBytes,
                            const std::string& whatItIs) {
    std::ifstream in = openInputFile(path, std::ios::binary);
    std::string text;
    char buffer[BoundedLines::kChunkBytes];
    while (in) {
        in.read(buffer, sizeof buffer);
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
        if (text.size() > maxBytes)
            throw InputError(path, "",
                             "the file is larger than " + sizeText(maxBytes) + ", more than " +
                                 whatItIs + " ever holds; give the right file");
    }
    if (in.bad()) throw InputError(path, "", "reading the file failed; check the disk");
    return text;
}

BoundedLines::BoundedLines(std::istream& in, std::string path, std::size_t maxLine,
                           std::string whatItIs)
    : in_(in), path_(std::move(path)), whatItIs_(std::move(whatItIs)), maxLine_(maxLine) {}

bool BoundedLines::next(std::string& line) {
    for (;;) {
        const std::size_t nl = buffer_.find('\n', start_);
        if (nl != std::string::npos && nl - start_ <= maxLine_) {
            line.assign(buffer_, start_, nl - start_);
            start_ = nl + 1;
            break;
        }
        if (buffer_.size() - start_ > maxLine_)
            throw InputError(path_, "line " + std::to_string(number_ + 1),
                             "the line is longer than " + sizeText(maxLine_) + "; " + whatItIs_);
        if (!in_) {  // the end: a last line without its newline
            if (start_ >= buffer_.size()) return false;
            line.assign(buffer_, start_, std::string::npos);
            start_ = buffer_.size();
            unterminated_ = true;
            break;
        }
        buffer_.erase(0, start_);
        start_ = 0;
        char chunk[kChunkBytes];
        in_.read(chunk, sizeof chunk);
        buffer_.append(chunk, static_cast<std::size_t>(in_.gcount()));
    }
    ++number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
}

}  // namespace activetouch
