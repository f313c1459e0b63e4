#include "app/run/OutputFiles.h"

#include <filesystem>
#include <fstream>

namespace activetouch {

namespace fs = std::filesystem;

void ensureOutputDirectory(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw InputError(
            dir, "",
            "cannot create the output folder (" + ec.message() + "); choose a writable --out");
}

std::FILE* openOutputTable(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f)
        throw InputError(path, "", "cannot write the file; check the output folder is writable");
    return f;
}

void writeJsonAtomically(const std::string& path, const Json& doc) {
    const std::string temp = path + ".partial";
    {
        std::ofstream out(temp);
        if (!out)
            throw InputError(temp, "",
                             "cannot write the file; check the output folder is writable");
        out << doc.dump(2) << '\n';
    }
    fs::rename(temp, path);
}

}  // namespace activetouch
