#pragma once
// Functions compiled twice, for AVX2 and for any x86-64, the loader picking the better for the CPU
// it runs on. Elsewhere, and under ThreadSanitizer (whose runtime is not yet up when the loader
// picks), only the portable build is made; each clone gives the same results.
#if defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
#define ACTIVETOUCH_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ACTIVETOUCH_AVX2_CLONES
#endif

namespace activetouch {

/// Whether the CPU this runs on has AVX2 and the POPCNT every AVX2 CPU has, for the kernels
/// written with AVX2 intrinsics beside a portable reading (always false off x86-64).
inline bool cpuHasAvx2() {
#if defined(__x86_64__)
    static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
    return avx2;
#else
    return false;
#endif
}

}  // namespace activetouch
