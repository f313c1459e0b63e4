#pragma once
// A disk that fills, on demand: while a FileSizeLimit lives, no file this process writes may grow
// past a size, and a write beyond it fails with EFBIG ("File too large") as a full disk's fails
// with ENOSPC, instead of the process being killed by SIGXFSZ.
#include <sys/resource.h>

#include <csignal>

namespace activetouch::test {

/// Limits the size of files this process writes to `bytes` (in a child about to start, say).
inline void limitFileSize(rlim_t bytes) {
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{};
    getrlimit(RLIMIT_FSIZE, &limit);
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
}

class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &before_);
        previous_ = std::signal(SIGXFSZ, SIG_IGN);
        limitFileSize(bytes);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &before_);
        std::signal(SIGXFSZ, previous_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
    rlimit before_{};
    void (*previous_)(int) = nullptr;
};

}  // namespace activetouch::test
