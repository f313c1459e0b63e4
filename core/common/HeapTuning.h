#pragma once
// The heap kept between runs: a sweep over seeds builds and frees the same working set (taps,
// tables, belief fits) once a seed, and glibc's defaults hand large freed blocks back to the
// system and take them again, a page fault per page each time (a seventh of a seeds run's time).
// Large blocks therefore come from the heap, and the heap keeps up to 512 MB it has freed.
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace activetouch {

inline void keepHeapBetweenRuns() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 256 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
    mallopt(M_TOP_PAD, 64 * 1024 * 1024);
#endif
}

}  // namespace activetouch
