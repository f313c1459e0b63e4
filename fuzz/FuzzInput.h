#pragma once
// What every harness shares: the input written to a file in the harness's own folder (the file
// readers are fuzzed through the same entry the command line uses), and the rule that an error
// a user can cause is an expected outcome while anything else escaping is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

namespace activetouch::fuzz {

/// The harness's folder under $TMPDIR (or /tmp), made once per process.
inline const std::string& folder() {
    static const std::string dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/activetouch-fuzz-XXXXXX";
        if (!mkdtemp(pattern.data())) std::abort();
        return pattern;
    }();
    return dir;
}

/// Writes `text` to `name` in the harness's folder; returns its path.
inline std::string writeFile(const std::string& name, const char* data, std::size_t size) {
    const std::string path = folder() + "/" + name;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(data, static_cast<std::streamsize>(size));
    return path;
}

inline std::string writeInput(const std::string& name, const std::uint8_t* data, std::size_t size) {
    return writeFile(name, reinterpret_cast<const char*>(data), size);
}

}  // namespace activetouch::fuzz
