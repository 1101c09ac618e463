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

inline void addHost(MemoryStats& m, MemoryGroup g, size_t bytes) { m.hostBytes[(int)g] += bytes; }

// The host state's arrays: owners, geometry, contacts and wildcards.
void countStateMemory(const SimState& s, MemoryStats& m);

}  // namespace deme
