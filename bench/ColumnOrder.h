// Points put in columns: the (x, y) plane cut into square tiles `tile` wide, the tiles' points one
// tile after the other (tiles in rows of x), each tile's in the order they came in. A sampler's
// lattice comes layer by layer, so a grain's neighbour in the layer below is a whole layer of ids
// before it (at a billion spheres in the mixer, 1.8 M grains, ~100 MB of their state), which no GPU
// cache holds until it is read again; in columns that distance is a tile's layer. For the mixer
// benchmark's `MIXER_ORDER=columns`, which measures what the order costs the force pass at scale.
#pragma once

#include <deme/VectorTypes.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace deme_bench {

// Reorders `p` by column (a stable counting sort by tile; one transient copy of the points).
inline void orderInColumns(std::vector<deme::float3>& p, float tile) {
    if (p.empty() || !(tile > 0.f)) return;
    float xmin = p[0].x, xmax = p[0].x, ymin = p[0].y, ymax = p[0].y;
    for (const deme::float3& q : p) {
        xmin = std::min(xmin, q.x);
        xmax = std::max(xmax, q.x);
        ymin = std::min(ymin, q.y);
        ymax = std::max(ymax, q.y);
    }
    const size_t nx = (size_t)std::floor((xmax - xmin) / tile) + 1, ny = (size_t)std::floor((ymax - ymin) / tile) + 1;
    auto tileOf = [&](const deme::float3& q) {
        const size_t i = std::min((size_t)((q.x - xmin) / tile), nx - 1);
        const size_t j = std::min((size_t)((q.y - ymin) / tile), ny - 1);
        return j * nx + i;
    };
    std::vector<size_t> start(nx * ny + 1, 0);
    for (const deme::float3& q : p) start[tileOf(q) + 1]++;
    for (size_t t = 0; t < nx * ny; t++) start[t + 1] += start[t];
    std::vector<deme::float3> out(p.size());
    for (const deme::float3& q : p) out[start[tileOf(q)]++] = q;
    p.swap(out);
}

}  // namespace deme_bench
