// Marks functions that the CPU compiler and the CUDA compilers (nvcc, NVRTC) all compile from the
// same text. Physics headers use only this macro, POD types and plain arithmetic.
#pragma once

#if defined(__CUDACC__) || defined(__CUDACC_RTC__)
#define DEME_HD __host__ __device__
#else
#define DEME_HD
#endif
