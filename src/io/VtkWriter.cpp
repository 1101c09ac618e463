#include "io/VtkWriter.h"

#include "io/AtomicFile.h"

#include <deme/Error.h>

#include <charconv>
#include <cstdio>

namespace deme {
namespace {

// Appends with to_chars: locale-independent, unlike printf, and much faster for millions of numbers.
void put(std::string& s, long long v) {
    char tmp[24];
    s.append(tmp, std::to_chars(tmp, tmp + sizeof tmp, v).ptr);
}

void put(std::string& s, float v) {
#if defined(__cpp_lib_to_chars)
    char tmp[32];
    s.append(tmp, std::to_chars(tmp, tmp + sizeof tmp, v).ptr);  // shortest text that reads back as v
#else
    char tmp[32];
    s.append(tmp, (size_t)std::snprintf(tmp, sizeof tmp, "%.9g", (double)v));  // 9 digits round-trip a float
#endif
}

}  // namespace

void writeVtkTriangles(const std::string& path, const std::vector<double3>& points, const std::vector<int3>& triangles,
                       const std::vector<int>& triangleOwner, const std::string& call) {
    // Validate first, so a bad call never leaves a half-written file behind.
    if (triangleOwner.size() != triangles.size())
        throwError(call, "cannot write '" + path + "': " + std::to_string(triangles.size()) + " triangles but " +
                             std::to_string(triangleOwner.size()) + " owner values");
    const long long np = (long long)points.size();
    for (size_t t = 0; t < triangles.size(); t++) {
        const int3& f = triangles[t];
        if (f.x < 0 || f.y < 0 || f.z < 0 || f.x >= np || f.y >= np || f.z >= np)
            throwError(call, "cannot write '" + path + "': triangle " + std::to_string(t) +
                                 " indexes a point outside 0.." + std::to_string(np - 1));
    }

    AtomicFile file(path, call);
    std::string s;
    // Text is built in ~1 MiB chunks so memory stays flat for huge meshes.
    auto flush = [&](bool force) {
        if (!force && s.size() < (1u << 20)) return;
        file.write(s);
        s.clear();
    };

    s += "# vtk DataFile Version 3.0\nDEM-Engine triangle mesh\nASCII\nDATASET POLYDATA\nPOINTS ";
    put(s, np);
    s += " float\n";
    for (const double3& p : points) {
        put(s, (float)p.x);
        s += ' ';
        put(s, (float)p.y);
        s += ' ';
        put(s, (float)p.z);
        s += '\n';
        flush(false);
    }
    // POLYGONS' second number is the total count of integers in the section: 4 per triangle.
    s += "POLYGONS ";
    put(s, (long long)triangles.size());
    s += ' ';
    put(s, 4 * (long long)triangles.size());
    s += '\n';
    for (const int3& f : triangles) {
        s += "3 ";
        put(s, (long long)f.x);
        s += ' ';
        put(s, (long long)f.y);
        s += ' ';
        put(s, (long long)f.z);
        s += '\n';
        flush(false);
    }
    s += "CELL_DATA ";
    put(s, (long long)triangles.size());
    s += "\nSCALARS owner int 1\nLOOKUP_TABLE default\n";
    for (int o : triangleOwner) {
        put(s, (long long)o);
        s += '\n';
        flush(false);
    }
    flush(true);
    file.commit();
}

}  // namespace deme
