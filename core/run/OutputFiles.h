#pragma once
// Writing a run's artefacts: the output folder, tables (core/io/OutputFile.h), and JSON documents
// written atomically (a reader either finds the whole document or none). Each failure names the
// file and what to do: an InputError for a folder or file that cannot be created, a WriteError
// for one that cannot be written whole.
#include <optional>
#include <string>

#include "core/io/JsonFields.h"
#include "core/io/OutputFile.h"

namespace activetouch {

void ensureOutputDirectory(const std::string& dir);

/// Opens `dir`/`tableName` into `table` for rows appended as they come, its `header` written and
/// flushed, and removes `dir`/`documentName`, the document written once the table is whole, so
/// that an earlier run's is never taken for this one's.
void startAppendedTable(std::optional<OutputFile>& table, const std::string& dir,
                        const std::string& tableName, const std::string& documentName,
                        const char* header);

/// Writes `doc` to `path` through `path`.partial and a rename; if writing fails, `path` is left as
/// it was and the partial file is removed.
void writeJsonAtomically(const std::string& path, const Json& doc);

}  // namespace activetouch
