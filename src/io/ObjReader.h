// Reader for Wavefront OBJ triangle meshes (mixer blades, drums, hoppers exported from CAD/Blender).
#pragma once

#include <string>
#include <vector>

#include <deme/Mesh.h>
#include <deme/VectorTypes.h>

namespace deme {

struct ObjMesh {
    std::vector<float3> vertices;
    std::vector<int3> faces;  // triangles, 0-based indices into vertices
};

// Reads `v x y z [w]` vertices (extra numeric fields such as w or vertex colours are ignored) and `f` faces
// whose vertex tokens have any of the forms `i`, `i/t`, `i//n`, `i/t/n`, with 1-based or negative (relative:
// -1 is the last vertex read so far) indices. Polygons with more than 3 vertices are fan-triangulated as
// (v0, vk, vk+1). Every other statement (vt, vn, o, g, s, usemtl, mtllib, l, p, ...) is ignored, as are blank
// lines and '#' comments (also trailing ones). Windows line endings and a UTF-8 byte-order mark are tolerated;
// '\' line continuations are not supported. Numbers are parsed independently of the C locale.
// Every error throws deme::Error via throwFileError(call, path, line, ...): unreadable file (line 0);
// non-numeric, non-finite or fewer than 3 vertex coordinates; a face with fewer than 3 vertices; a malformed
// index token; index 0; a negative index reaching before the first vertex; a positive index beyond the
// file's total vertex count (checked after the whole file is read, so it is reported after any syntax error
// further down, but still at the face's line); a file without faces (at its last line).
ObjMesh readObj(const std::string& path, const std::string& call);

}  // namespace deme
