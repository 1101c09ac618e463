// A bladed mixer built in code: a central hub (a closed cylinder) and flat, optionally pitched blades
// (thin closed boxes of 12 triangles each) radiating from it. Used by DEMdemo_Mixer, which writes it
// as a Wavefront OBJ file and loads it back with AddWavefrontMeshObject, so no data file is needed.
//
// The mesh frame: z is the rotation axis, the origin is the middle of the hub (the centre of the
// mixer's height). A prescribed spin about the mesh's z axis therefore turns the mixer about its hub,
// and the contact torque a tracker reports (about the mesh origin) is the torque about the shaft.
#pragma once

#include <deme/deme.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace mixer_geometry {

struct MixerSpec {
    float hub_radius = 0.06f;      // radius of the central hub
    float height = 0.3f;           // hub and blade height (along z), centred on z = 0
    float tip_radius = 0.49f;      // no point of the mixer lies farther than this from the axis
    float blade_thickness = 0.02f;
    float pitch_deg = 15.f;        // blade tilt about its own radial axis (0: vertical, flat blades)
    int num_blades = 4;
    int hub_segments = 32;         // facets around the hub
};

struct TriMesh {
    std::vector<deme::float3> vertices;
    std::vector<deme::int3> faces;  // 0-based, counter-clockwise seen from outside (normals outward)

    // Appends a closed box given by its 8 corners, indexed as bit 0 -> +x, bit 1 -> +y, bit 2 -> +z
    // of the box's own frame (the corners may be rotated arbitrarily): 6 faces, 12 triangles.
    void addBox(const deme::float3 (&c)[8]) {
        const int b = (int)vertices.size();
        for (const auto& p : c) vertices.push_back(p);
        // Each face as 4 corner indices in counter-clockwise order seen from outside.
        static const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                        {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& q : quads) {
            faces.push_back(deme::make_int3(b + q[0], b + q[1], b + q[2]));
            faces.push_back(deme::make_int3(b + q[0], b + q[2], b + q[3]));
        }
    }

    // Appends a closed cylinder about z: n side quads (2n triangles) and two fans of n triangles.
    void addCylinderZ(float radius, float z0, float z1, int n) {
        const int b = (int)vertices.size();
        const double two_pi = 6.283185307179586;
        for (int i = 0; i < n; i++) {
            const double a = two_pi * i / n;
            const float x = (float)(radius * std::cos(a)), y = (float)(radius * std::sin(a));
            vertices.push_back(deme::make_float3(x, y, z0));  // b + 2i
            vertices.push_back(deme::make_float3(x, y, z1));  // b + 2i + 1
        }
        const int bottom = (int)vertices.size();
        vertices.push_back(deme::make_float3(0.f, 0.f, z0));
        const int top = (int)vertices.size();
        vertices.push_back(deme::make_float3(0.f, 0.f, z1));
        for (int i = 0; i < n; i++) {
            const int j = (i + 1) % n;
            const int lo_i = b + 2 * i, hi_i = lo_i + 1, lo_j = b + 2 * j, hi_j = lo_j + 1;
            faces.push_back(deme::make_int3(lo_i, lo_j, hi_j));
            faces.push_back(deme::make_int3(lo_i, hi_j, hi_i));
            faces.push_back(deme::make_int3(bottom, lo_j, lo_i));
            faces.push_back(deme::make_int3(top, hi_i, hi_j));
        }
    }

    float maxRadius() const {
        float r = 0.f;
        for (const auto& v : vertices) r = std::max(r, std::sqrt(v.x * v.x + v.y * v.y));
        return r;
    }

    // Wavefront OBJ (1-based indices). Returns false if the file cannot be written.
    bool writeObj(const std::string& path, const std::string& comment) const {
        std::FILE* fp = std::fopen(path.c_str(), "w");
        if (!fp) return false;
        std::fprintf(fp, "# %s\n# %zu vertices, %zu triangles\n", comment.c_str(), vertices.size(), faces.size());
        for (const auto& v : vertices) std::fprintf(fp, "v %.9g %.9g %.9g\n", v.x, v.y, v.z);
        for (const auto& f : faces) std::fprintf(fp, "f %d %d %d\n", f.x + 1, f.y + 1, f.z + 1);
        return std::fclose(fp) == 0;
    }
};

// The hub plus num_blades blades at equal angles. Each blade is a box spanning radially from inside
// the hub to the tip, tilted by pitch_deg about its radial axis; its outer end is placed so that its
// farthest corner lies exactly at tip_radius.
inline TriMesh MakeMixer(const MixerSpec& s) {
    TriMesh m;
    const float h = 0.5f * s.height, t = 0.5f * s.blade_thickness;
    m.addCylinderZ(s.hub_radius, -h, h, s.hub_segments);
    const double pitch = s.pitch_deg * 3.141592653589793 / 180.0;
    const float cp = (float)std::cos(pitch), sp = (float)std::sin(pitch);
    // A corner (x, y, z) of the untilted blade maps to (x, y cp - z sp, y sp + z cp): the farthest
    // from the axis has |y'| = t cp + h sp.
    const float y_far = t * cp + h * std::fabs(sp);
    const float x_out = std::sqrt(std::max(s.tip_radius * s.tip_radius - y_far * y_far, 0.f));
    const float x_in = 0.5f * s.hub_radius;  // the blade root is buried in the hub
    for (int k = 0; k < s.num_blades; k++) {
        const double a = 6.283185307179586 * k / s.num_blades;
        const float ca = (float)std::cos(a), sa = (float)std::sin(a);
        deme::float3 c[8];
        for (int i = 0; i < 8; i++) {
            const float x = (i & 1) ? x_out : x_in;
            const float y = (i & 2) ? t : -t;
            const float z = (i & 4) ? h : -h;
            const float yp = y * cp - z * sp, zp = y * sp + z * cp;  // pitch about the radial (x) axis
            c[i] = deme::make_float3(x * ca - yp * sa, x * sa + yp * ca, zp);
        }
        m.addBox(c);
    }
    return m;
}

}  // namespace mixer_geometry
