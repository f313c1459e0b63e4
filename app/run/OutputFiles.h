#pragma once
// Writing a run's artefacts: the output folder, tables, and JSON documents written atomically (a
// reader either finds the whole document or none). Each failure is an InputError naming the file
// and what to do.
#include <cstdio>
#include <string>

#include "core/io/JsonFields.h"

namespace activetouch {

void ensureOutputDirectory(const std::string& dir);

/// Opens `path` for writing; the caller closes it.
std::FILE* openOutputTable(const std::string& path);

/// Writes `doc` to `path` through `path`.partial and a rename.
void writeJsonAtomically(const std::string& path, const Json& doc);

}  // namespace activetouch
