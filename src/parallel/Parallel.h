// Thread counts and ranges for the OpenMP loops of the CPU backend and of host-side helpers: OpenMP
// when available, serial otherwise. Small loops stay serial, since waking the thread team costs more
// than they do.
#pragma once

#include <cstddef>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace deme {

constexpr size_t PARALLEL_MIN_ITEMS = 2048;

inline int cpuThreadCount() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

// Cores the OpenMP runtime sees (OMP_NUM_THREADS does not change it).
inline int cpuCoreCount() {
#ifdef _OPENMP
    return omp_get_num_procs();
#else
    return 1;
#endif
}

inline void setCpuThreadCount(int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
}

// Fewest cores for which contact detection gets a thread of its own by default.
constexpr int ASYNC_MIN_CORES = 8;

inline int cpuThreadIndex() {
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

// Contiguous share [begin, end) of n items for thread t of T: the split depends only on n and T,
// so per-thread results concatenated in thread order are deterministic.
inline void threadRange(size_t n, int t, int T, size_t& begin, size_t& end) {
    begin = n * (size_t)t / (size_t)T;
    end = n * (size_t)(t + 1) / (size_t)T;
}

// f(t, begin, end) for each thread t of T, in parallel, over its share of n items (threadRange):
// counts per share, summed in thread order, give each item a place that depends only on n and T.
template <class F>
inline void forEachThreadShare(size_t n, int T, F&& f) {
#pragma omp parallel num_threads(T) if (T > 1)
    {
        const int t = T > 1 ? cpuThreadIndex() : 0;
        size_t begin, end;
        threadRange(n, t, T, begin, end);
        f(t, begin, end);
    }
}

}  // namespace deme
