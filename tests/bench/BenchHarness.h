#pragma once
// A small benchmark harness: repeats a workload, reports the median per-iteration time beside
// its budget. Figures, not verdicts: nothing here fails on time.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

namespace activetouch::bench {

/// Median microseconds per call of `work` over `rounds` rounds of `iterations` calls.
inline double medianMicroseconds(const std::function<void()>& work, int iterations,
                                 int rounds = 7) {
    std::vector<double> perCall;
    for (int r = 0; r < rounds; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < iterations; ++i) work();
        const auto t1 = std::chrono::steady_clock::now();
        perCall.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count() / iterations);
    }
    std::sort(perCall.begin(), perCall.end());
    return perCall[perCall.size() / 2];
}

/// The clock this process gets, in GHz: a chain of dependent additions, one a cycle on the
/// machines of docs/benchmarks.md, timed over about 0.15 s. It falls when the core runs slower or
/// others take it in turns. It does not see another program on the core's second hardware thread,
/// which slows work that fills the core but not this chain.
inline double effectiveGigahertz() {
    constexpr long kAdds = 400'000'000;
    unsigned long x = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < kAdds; i += 4) {
        // The empty asm keeps each addition a separate step the compiler cannot fold.
        x += 1;
        asm volatile("" : "+r"(x));
        x += 1;
        asm volatile("" : "+r"(x));
        x += 1;
        asm volatile("" : "+r"(x));
        x += 1;
        asm volatile("" : "+r"(x));
    }
    const auto t1 = std::chrono::steady_clock::now();
    return static_cast<double>(x) / std::chrono::duration<double, std::nano>(t1 - t0).count();
}

inline void reportClock(const char* when) {
    std::printf("%-52s %10.2f GHz  (a chain of dependent additions)\n", when, effectiveGigahertz());
}

inline void report(const char* what, double value, const char* unit, double budget) {
    std::printf("%-52s %10.3f %-3s  (budget <= %g %s)  %s\n", what, value, unit, budget, unit,
                value <= budget ? "within budget" : "OVER BUDGET");
}

}  // namespace activetouch::bench
