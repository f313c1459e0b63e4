#pragma once
// A frames import on disk (docs/real-fingertips.md): `frames.json` (the layout, each file read with
// its frame count and SHA-256) and `frames.csv` (a row per file, frame and finger: its taxels'
// pressure counts), as `activetouch-cli import-frames` writes it and `fingertip-stats` reads it.
#include <string>
#include <vector>

#include "core/records/FramesTable.h"

namespace activetouch {

struct FramesImport {
    Json layoutDocument;
    FramesLayout layout;
    std::vector<FramesFile> files;  ///< path: the file's name as imported
};

/// Writes `folder`/frames.csv and frames.json (the folder must exist).
void writeFramesImport(const std::string& folder, const FramesImport& frames,
                       const std::vector<std::string>& digests);

/// Reads a folder import-frames wrote. Throws InputError naming the file and line.
FramesImport readFramesImport(const std::string& folder);

}  // namespace activetouch
