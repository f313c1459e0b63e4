#pragma once
// Opening a file the user named: a missing file, a folder or an unreadable file is an InputError
// that says which and what to do, before anything tries to parse it.
#include <fstream>
#include <string>

namespace activetouch {

/// `path` opened for reading. Throws InputError naming `path` if it does not exist, is a folder,
/// is no regular file (a device, a pipe, a socket) or cannot be read.
std::ifstream openInputFile(const std::string& path, std::ios::openmode mode = std::ios::in);

}  // namespace activetouch
