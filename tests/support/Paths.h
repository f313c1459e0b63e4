#pragma once
// Where tests find the source tree (experiments/, resources/) and the built CLI; set per test by
// CMake.
#include <QString>
#include <cstdlib>
#include <string>

namespace activetouch::test {

inline std::string sourceDir() {
    const char* s = std::getenv("ACTIVETOUCH_SOURCE_DIR");
    return s ? s : ".";
}

inline std::string sourcePath(const std::string& relative) {
    return sourceDir() + "/" + relative;
}

inline QString sourceFile(const QString& relative) {
    return QString::fromStdString(sourcePath(relative.toStdString()));
}

}  // namespace activetouch::test
