// Marks functions that the CPU compiler and the CUDA compilers (nvcc, NVRTC) all compile from the
// same text. Physics headers use only this macro, POD types and plain arithmetic.
//
// It also supplies the few standard names those headers need. NVRTC (__CUDACC_RTC__) compiles
// without a standard library: it predefines size_t and the math functions (sqrtf, fabs, logf, ...)
// but no <stdint.h>, so the fixed-width integers are declared here for it. Host and nvcc builds get
// the real headers and are unchanged.
#pragma once

#if defined(__CUDACC_RTC__)
// The very types libcu++'s <cuda/std/cstdint> declares under NVRTC, so that a kernel may include
// either first (an alias may be redeclared to the same type). uint64_t is unsigned long long here
// and unsigned long on a 64-bit Linux host: same size and representation, which is all that host
// and device share (flat arrays, extern "C" kernels).
typedef signed char int8_t;
typedef signed short int16_t;
typedef signed int int32_t;
typedef signed long long int64_t;
typedef unsigned char uint8_t;
typedef unsigned short uint16_t;
typedef unsigned int uint32_t;
typedef unsigned long long uint64_t;
#else
#include <stddef.h>
#include <stdint.h>
#endif

#if defined(__CUDACC__) || defined(__CUDACC_RTC__)
#define DEME_HD __host__ __device__
#define DEME_HD_INLINE __host__ __device__ __forceinline__
// Kept out of line where inlined code would hold registers that a hot loop needs (a rare path).
#define DEME_HD_NOINLINE __host__ __device__ __noinline__
#else
#define DEME_HD
#if defined(__GNUC__)
// Per-contact code is inlined whole into its loop, so that whatever a model does not use is
// never computed.
#define DEME_HD_INLINE inline __attribute__((always_inline))
#else
#define DEME_HD_INLINE inline
#endif
#define DEME_HD_NOINLINE inline
#endif
