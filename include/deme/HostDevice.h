// Marks functions that the CPU compiler and the CUDA compilers (nvcc, NVRTC) all compile from the
// same text. Physics headers use only this macro, POD types and plain arithmetic.
#pragma once

#if defined(__CUDACC__) || defined(__CUDACC_RTC__)
#define DEME_HD __host__ __device__
#define DEME_HD_INLINE __host__ __device__ __forceinline__
#else
#define DEME_HD
#if defined(__GNUC__)
// Per-contact code is inlined whole into its loop, so that whatever a model does not use is
// never computed.
#define DEME_HD_INLINE inline __attribute__((always_inline))
#else
#define DEME_HD_INLINE inline
#endif
#endif
