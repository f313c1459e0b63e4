#include "core/io/InputFile.h"

#include <filesystem>
#include <system_error>

#include "core/common/InputError.h"

namespace activetouch {

std::ifstream openInputFile(const std::string& path, std::ios::openmode mode) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "", "this is a folder, not a file; give the path of a file in it");
    // A pipe with no writer would block the open forever, a device never end: only regular
    // files are read.
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        throw InputError(path, "",
                         "this is not a regular file (a device, a pipe or a socket); give the "
                         "path of a file");
    std::ifstream in(path, mode);
    if (!in) {
        const bool exists = std::filesystem::exists(path, ec);
        throw InputError(path, "",
                         exists ? "cannot read the file; check its permissions"
                                : "no such file; check the path");
    }
    return in;
}

}  // namespace activetouch
