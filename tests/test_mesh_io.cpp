// OBJ mesh reading and legacy-VTK triangle output.
#include <deme/Error.h>
#include <gtest/gtest.h>

#include "ScratchDirTest.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/ObjReader.h"
#include "io/VtkWriter.h"

using namespace deme;
namespace fs = std::filesystem;

namespace {

class MeshIO : public deme_test::ScratchDirTest {
  protected:
    // The reader must throw deme::Error naming the call, the file and the line.
    void expectError(const std::string& text, size_t line, const std::string& fragment) {
        const std::string path = write("bad.obj", text);
        try {
            readObj(path, "AddWavefrontMeshObject");
            ADD_FAILURE() << "no throw for:\n" << text;
        } catch (const Error& e) {
            const std::string w = e.what();
            EXPECT_NE(w.find("AddWavefrontMeshObject"), std::string::npos) << w;
            EXPECT_NE(w.find(path + ":" + std::to_string(line) + ":"), std::string::npos) << w;
            EXPECT_NE(w.find(fragment), std::string::npos) << w;
        }
    }
};

std::string sharedObj(const std::string& name) {
#ifdef DEME_SHARED_DATA_DIR
    const std::string p = std::string(DEME_SHARED_DATA_DIR) + "/" + name;
    return fs::exists(p) ? p : std::string();
#else
    (void)name;
    return std::string();
#endif
}

// Vertex of triangle t, corner k (0..2), for checking that indices resolved to the intended vertex.
float3 corner(const ObjMesh& m, size_t t, int k) {
    const int3& f = m.faces.at(t);
    return m.vertices.at(k == 0 ? f.x : k == 1 ? f.y : f.z);
}

}  // namespace

TEST_F(MeshIO, SharedInternalMixer) {
    const std::string path = sharedObj("internal_mixer.obj");
    if (path.empty()) GTEST_SKIP() << "internal_mixer.obj not available";
    const ObjMesh m = readObj(path, "test");
    EXPECT_EQ(m.faces.size(), 2892u);  // 5 objects, `i//n` faces, `o`/`s` lines ignored
    EXPECT_EQ(m.vertices.size(), 1516u);
}

TEST_F(MeshIO, SharedCubeAndSphere) {
    const std::string cube = sharedObj("cube.obj"), sphere = sharedObj("sphere.obj");
    if (cube.empty() || sphere.empty()) GTEST_SKIP() << "cube.obj / sphere.obj not available";
    const ObjMesh c = readObj(cube, "test");  // CRLF line ends
    EXPECT_EQ(c.faces.size(), 12u);           // 12 triangles on 24 vertices
    EXPECT_EQ(c.vertices.size(), 24u);
    const ObjMesh s = readObj(sphere, "test");  // Blender icosphere with mtllib/usemtl
    EXPECT_EQ(s.faces.size(), 320u);            // 320 triangles on 162 vertices
    EXPECT_EQ(s.vertices.size(), 162u);
}

TEST_F(MeshIO, PolygonsAreFanTriangulated) {
    const ObjMesh m = readObj(write("poly.obj",
                                    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                                    "f 1 2 3 4\n"    // quad -> 2
                                    "f 1 2 3 5 4\n"  // pentagon -> 3
                                    "f 4 3 2 1\n"),  // quad -> 2
                              "test");
    ASSERT_EQ(m.faces.size(), 7u);
    // Fan around the first vertex: (v0, vk, vk+1).
    const int expect[7][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 4}, {0, 4, 3}, {3, 2, 1}, {3, 1, 0}};
    for (int t = 0; t < 7; t++) {
        EXPECT_EQ(m.faces[t].x, expect[t][0]) << t;
        EXPECT_EQ(m.faces[t].y, expect[t][1]) << t;
        EXPECT_EQ(m.faces[t].z, expect[t][2]) << t;
    }
}

TEST_F(MeshIO, IndexFormsAndNegativeIndicesResolve) {
    const ObjMesh m = readObj(write("forms.obj",
                                    "# header\n\n"
                                    "mtllib x.mtl\no thing\ng group\ns off\nusemtl steel\n"
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0 1.0\n"  // optional w
                                    "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                                    "f 1 2 3\n"
                                    "f 1/1 2/2 3/3\n"
                                    "f 1//1 2//1 3//1\n"
                                    "f 1/1/1 2/2/1 3/3/1\n"
                                    "v +2 -0 3.5e0  # trailing comment\n"  // vertex 4
                                    "f -4 -3/1 -1//1\n"                    // -> 1 2 4
                                    "f -1/-1/-1 1 -2\n"                    // -> 4 1 3
                                    "l 1 2\np 3\n"),
                              "test");
    ASSERT_EQ(m.vertices.size(), 4u);
    ASSERT_EQ(m.faces.size(), 6u);
    for (int t = 0; t < 4; t++) {
        EXPECT_EQ(m.faces[t].x, 0);
        EXPECT_EQ(m.faces[t].y, 1);
        EXPECT_EQ(m.faces[t].z, 2);
    }
    EXPECT_FLOAT_EQ(corner(m, 4, 0).x, 0.f);
    EXPECT_FLOAT_EQ(corner(m, 4, 1).x, 1.f);
    EXPECT_FLOAT_EQ(corner(m, 4, 2).x, 2.f);
    EXPECT_FLOAT_EQ(corner(m, 4, 2).z, 3.5f);
    EXPECT_EQ(m.faces[5].x, 3);
    EXPECT_EQ(m.faces[5].y, 0);
    EXPECT_EQ(m.faces[5].z, 2);
    EXPECT_FLOAT_EQ(corner(m, 5, 2).y, 1.f);
}

TEST_F(MeshIO, ForwardReferencesAreCheckedAgainstTheTotal) {
    // Faces before their vertices are legal OBJ; only the final vertex count decides.
    const ObjMesh m = readObj(write("fwd.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"), "test");
    ASSERT_EQ(m.faces.size(), 1u);
    EXPECT_FLOAT_EQ(corner(m, 0, 1).x, 1.f);
}

TEST_F(MeshIO, WindowsLineEndingsAndBom) {
    const ObjMesh m = readObj(write("crlf.obj",
                                    "\xEF\xBB\xBFv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 1 1 0\r\n\r\n"
                                    "f 1//1 2//1 3//1\r\nf 2 4 3\r\n"),  // no '\n' after the last line
                              "test");
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.faces[1].x, 1);
    EXPECT_EQ(m.faces[1].y, 3);
    EXPECT_EQ(m.faces[1].z, 2);
    EXPECT_FLOAT_EQ(m.vertices[3].y, 1.f);
}

TEST_F(MeshIO, ErrorsNameCallFileAndLine) {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    expectError(tri + "f 1 2 x\n", 4, "malformed");
    expectError(tri + "f 1 2 3/\n", 4, "malformed");
    expectError(tri + "f 1 2 3//\n", 4, "malformed");
    expectError(tri + "f 1 2 3/1/1/1\n", 4, "malformed");
    expectError(tri + "f 1 2 3a\n", 4, "malformed");
    expectError("v 0 0 0\nv 1 abc 0\n", 2, "abc");
    expectError("v 0 0 0\nv 1 0 nan\n", 2, "finite");
    expectError("v 0 0 0\nv 1 0 1e99\n", 2, "finite");  // overflows float
    expectError("v 0 0 0\nv 1,5 0 0\n", 2, "1,5");      // decimal comma is not a number
    expectError("v 0 0 0\r\nv 1 0\r\n", 2, "coordinates");
    expectError(tri + "f 0 1 2\n", 4, "index 0");
    expectError(tri + "f 1 2 3\nf 1 2 4\n# end\n", 5, "out of range");  // reported at the face, after reading all
    expectError(tri + "f 1 2 99999999999999999999\n", 4, "out of range");
    expectError(tri + "f -1 -2 -4\n", 4, "-4");
    expectError(tri + "\nf 1 2\n", 5, "expected at least 3");
    expectError(tri + "l 1 2\n", 4, "no faces");
}

TEST_F(MeshIO, MissingFileIsLineZero) {
    const std::string path = (dir / "does_not_exist.obj").string();
    try {
        readObj(path, "AddWavefrontMeshObject");
        ADD_FAILURE() << "no throw";
    } catch (const Error& e) {
        const std::string w = e.what();
        EXPECT_NE(w.find("AddWavefrontMeshObject"), std::string::npos) << w;
        EXPECT_NE(w.find(path + ":0:"), std::string::npos) << w;
    }
}

TEST_F(MeshIO, VtkTwoTrianglesRoundTrip) {
    const std::string path = (dir / "mesh.vtk").string();
    const std::vector<double3> pts = {make_double3(0, 0, 0), make_double3(1.5, 0, 0), make_double3(0, 2, 0),
                                      make_double3(1, 1, -0.25)};
    writeVtkTriangles(path, pts, {make_int3(0, 1, 2), make_int3(1, 3, 2)}, {7, -1}, "WriteMeshFile");

    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    ASSERT_EQ(lines.size(), 5u + 4u + 1u + 2u + 3u + 2u);
    EXPECT_EQ(lines[0], "# vtk DataFile Version 3.0");
    EXPECT_FALSE(lines[1].empty());  // title line
    EXPECT_EQ(lines[2], "ASCII");
    EXPECT_EQ(lines[3], "DATASET POLYDATA");
    EXPECT_EQ(lines[4], "POINTS 4 float");
    std::istringstream p5(lines[5 + 3]);  // 4th point
    double x, y, z;
    p5 >> x >> y >> z;
    EXPECT_DOUBLE_EQ(x, 1.0);
    EXPECT_DOUBLE_EQ(y, 1.0);
    EXPECT_DOUBLE_EQ(z, -0.25);
    std::istringstream p2(lines[5 + 1]);
    p2 >> x;
    EXPECT_DOUBLE_EQ(x, 1.5);
    EXPECT_EQ(lines[9], "POLYGONS 2 8");
    EXPECT_EQ(lines[10], "3 0 1 2");
    EXPECT_EQ(lines[11], "3 1 3 2");
    EXPECT_EQ(lines[12], "CELL_DATA 2");
    EXPECT_EQ(lines[13], "SCALARS owner int 1");
    EXPECT_EQ(lines[14], "LOOKUP_TABLE default");
    EXPECT_EQ(lines[15], "7");
    EXPECT_EQ(lines[16], "-1");
}

TEST_F(MeshIO, VtkErrorsNameCallAndPath) {
    const std::vector<double3> pts = {make_double3(0, 0, 0), make_double3(1, 0, 0), make_double3(0, 1, 0)};
    const std::string unwritable = (dir / "no_such_dir" / "mesh.vtk").string();
    const std::string ok = (dir / "mesh.vtk").string();
    struct Case {
        std::string path;
        std::vector<int3> tris;
        std::vector<int> owner;
    };
    const Case cases[] = {{unwritable, {make_int3(0, 1, 2)}, {0}},
                          {ok, {make_int3(0, 1, 2)}, {}},    // owner count mismatch
                          {ok, {make_int3(0, 1, 3)}, {0}}};  // index past the points
    for (const Case& c : cases) {
        try {
            writeVtkTriangles(c.path, pts, c.tris, c.owner, "WriteMeshFile");
            ADD_FAILURE() << "no throw for " << c.path;
        } catch (const Error& e) {
            const std::string w = e.what();
            EXPECT_NE(w.find("WriteMeshFile"), std::string::npos) << w;
            EXPECT_NE(w.find(c.path), std::string::npos) << w;
        }
    }
    EXPECT_FALSE(fs::exists(ok));  // invalid input is rejected before the file is created
}
