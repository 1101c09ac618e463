// Host memory by array group (MemoryGroup, include/deme/MemoryStats.h): each array counts its
// capacity. The device side is counted by the device buffers themselves (backend/cuda/DeviceBuffer.h).
#pragma once

#include <deme/MemoryStats.h>

#include <vector>

#include "state/SimState.h"

namespace deme {

template <class T>
size_t vectorBytes(const std::vector<T>& v) {
    return v.capacity() * sizeof(T);
}

// Frees a vector's storage (`v = {}` assigns an empty list and keeps the capacity; so does clear()).
template <class T>
void releaseVector(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

inline void addHost(MemoryStats& m, MemoryGroup g, size_t bytes) { m.hostBytes[(int)g] += bytes; }

// The host state's arrays: owners, geometry, contacts and wildcards.
void countStateMemory(const SimState& s, MemoryStats& m);

}  // namespace deme
