#include "core/run/OutputFiles.h"

#include <filesystem>

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

void startAppendedTable(std::optional<OutputFile>& table, const std::string& dir,
                        const std::string& tableName, const std::string& documentName,
                        const char* header) {
    ensureOutputDirectory(dir);
    std::error_code ec;
    fs::remove(fs::path(dir) / documentName, ec);
    table.emplace((fs::path(dir) / tableName).string());
    table->print("%s", header);
    table->flush();
}

void writeJsonAtomically(const std::string& path, const Json& doc) {
    const std::string temp = path + ".partial";
    try {
        OutputFile out(temp);
        const std::string text = doc.dump(2);
        out.print("%s\n", text.c_str());
        out.close();
    } catch (const WriteError& e) {  // the partial file is no document: named by its own path
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw WriteError(path, e.reason(),
                         "free space on its disk or choose another output folder, and run again");
    } catch (...) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw;
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        const std::string reason = ec.message();
        fs::remove(temp, ec);
        throw WriteError(path, reason,
                         "check that the output folder is writable and that nothing else stands "
                         "at that path");
    }
}

}  // namespace activetouch
