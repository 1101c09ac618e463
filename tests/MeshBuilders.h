// Small meshes built in code for the mesh tests.
#pragma once

#include <vector>

#include <deme/deme.h>

namespace deme_test {

using namespace deme;

// The square [x0, x0 + n h] x [y0, y0 + n h] at height z, as 2 n^2 triangles facing +z; diagonals
// alternate so that vertices have 4 or 8 triangles around them.
inline DEMMeshConnected gridFloor(float x0, float y0, float z, int n, float h, std::shared_ptr<DEMMaterial> mat) {
    std::vector<float3> v;
    std::vector<int3> f;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) v.push_back(make_float3(x0 + i * h, y0 + j * h, z));
    auto id = [&](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if ((i + j) % 2 == 0) {
                f.push_back(make_int3(a, b, c));
                f.push_back(make_int3(a, c, d));
            } else {
                f.push_back(make_int3(a, b, d));
                f.push_back(make_int3(b, c, d));
            }
        }
    return DEMMeshConnected(v, f, mat);
}

// Axis-aligned box [lo, hi] as 12 triangles (two-sided, so orientation does not matter).
inline DEMMeshConnected boxMesh(const float3& lo, const float3& hi, std::shared_ptr<DEMMaterial> mat) {
    std::vector<float3> v;
    for (int k = 0; k < 8; k++)
        v.push_back(make_float3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z));
    std::vector<int3> f = {make_int3(0, 1, 3), make_int3(0, 3, 2), make_int3(4, 5, 7), make_int3(4, 7, 6),
                           make_int3(0, 1, 5), make_int3(0, 5, 4), make_int3(2, 3, 7), make_int3(2, 7, 6),
                           make_int3(0, 2, 6), make_int3(0, 6, 4), make_int3(1, 3, 7), make_int3(1, 7, 5)};
    return DEMMeshConnected(v, f, mat);
}

}  // namespace deme_test
