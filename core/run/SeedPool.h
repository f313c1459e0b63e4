#pragma once
// Runs over seeds on several cores, reported in seed order. Each seed's run is a pure function of
// the seed (its own data sets, noise and trials), so running seeds side by side changes nothing
// but the wall time: every table row, figure and rate is the same as one seed after another.
#include <cstdint>
#include <deque>
#include <future>
#include <thread>
#include <utility>

namespace activetouch {

/// How many seeds run at once unless told: one per core the system reports (at least one).
inline int defaultSeedJobs() {
    const unsigned cores = std::thread::hardware_concurrency();
    return cores == 0 ? 1 : static_cast<int>(cores);
}

/// Computes `compute(seed)` for the seeds `first`..`last` on up to `jobs` threads and hands each
/// result to `consume(seed, result)` on the calling thread, in seed order, once it and every seed
/// before it are done. `consume` returning false stops: no further seed starts, and those already
/// running are finished and dropped. An exception from `compute` reaches the caller when its seed's
/// turn comes, after every seed before it has been consumed.
template <typename Compute, typename Consume>
void forEachSeed(std::uint64_t first, std::uint64_t last, int jobs, Compute compute,
                 Consume consume) {
    using Result = decltype(compute(first));
    std::deque<std::pair<std::uint64_t, std::future<Result>>> running;
    std::uint64_t next = first;
    bool more = first <= last;
    const auto start = [&] {
        running.emplace_back(next, std::async(std::launch::async, compute, next));
        if (next == last)
            more = false;  // last may be the largest seed
        else
            ++next;
    };
    const std::size_t width = static_cast<std::size_t>(jobs < 1 ? 1 : jobs);
    while (more || !running.empty()) {
        while (more && running.size() < width) start();
        auto [seed, result] = std::move(running.front());
        running.pop_front();
        if (!consume(seed, result.get())) break;
    }
    // Leaving drops the seeds still running once they finish (each future waits for its own).
}

}  // namespace activetouch
