#pragma once
// SHA-256 of a file, to prove that a run folder's files are the ones its run wrote (run.json
// records each file's size and digest; merge, replay, analyse and check verify them). Computed
// with OpenSSL's libcrypto, the digest every Debian system already trusts.
#include <string>

namespace activetouch {

/// The SHA-256 of the file at `path` as 64 lowercase hex digits, read in chunks. Throws
/// InputError naming the file if it is no regular file or cannot be read.
std::string sha256OfFile(const std::string& path);

/// The SHA-256 of `bytes`, as sha256OfFile gives it.
std::string sha256Of(const std::string& bytes);

}  // namespace activetouch
