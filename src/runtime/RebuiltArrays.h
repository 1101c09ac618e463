// Arrays rebuilt at every detection (the GPU's contact set ids and detection scratch, the CPU's
// bins) are let go between detections where they are large, and kept where they are small: a large
// scene's memory at its peak, against no allocation per detection for a lab-scale run, whose bytes
// do not matter (docs/memory.md).
#pragma once

#include <cstddef>

namespace deme {

// The bytes up to which such an array is kept: KEEP_REBUILT_ARRAYS_UP_TO (state/SimState.h), or the
// environment variable DEME_SMALL_CONTACT_SET_BYTES where set (0 treats every array as large: the
// tests' way to reach the large scenes' path with a small one). A value that is not a number of
// bytes is a deme::Error from `call`.
size_t keepRebuiltArraysUpTo(const char* call);

}  // namespace deme
