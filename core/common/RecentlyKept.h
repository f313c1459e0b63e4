#pragma once
// A few values kept for the whole process by key, the oldest let go past a bound: what is worked
// out once from its inputs alone (a fingertip's contact patch, a contour's reach) and asked for
// again by every run and trial, whichever thread runs it.
#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace activetouch {

template <class Key, class Value, std::size_t Kept>
class RecentlyKept {
public:
    /// The value kept for `key`, or the one `make()` returns, kept (the oldest let go past Kept).
    /// Made under the lock: threads asking for the same key at once make it once.
    template <class Make>
    std::shared_ptr<const Value> get(const Key& key, Make make) {
        std::lock_guard lock(mutex_);
        for (const auto& [k, v] : kept_)
            if (k == key) return v;
        if (kept_.size() >= Kept) kept_.erase(kept_.begin());
        kept_.emplace_back(key, make());
        return kept_.back().second;
    }

private:
    std::mutex mutex_;
    std::vector<std::pair<Key, std::shared_ptr<const Value>>> kept_;
};

}  // namespace activetouch
