// Triangle meshes: rigid bodies made of triangles (mixer blades, hoppers, wheels, plows).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Materials.h"
#include "VariableTypes.h"

namespace deme {

struct int3 {
    int x, y, z;
};
inline int3 make_int3(int x, int y, int z) { return int3{x, y, z}; }

// A mesh owner. Vertices are in the mesh's own frame, whose origin is taken as its centre of mass
// (and MOI as principal moments about that frame's axes). A mesh is fixed unless its family
// prescribes motion or it has been given a mass with SetMass, which makes it a free body.
class DEMMeshConnected {
  public:
    DEMMeshConnected() = default;
    // Faces index into vertices (0-based); one material for all triangles.
    DEMMeshConnected(std::vector<float3> vertices, std::vector<int3> faces, std::shared_ptr<DEMMaterial> mat);

    void Scale(float s);
    void Scale(const float3& s);  // per axis
    void SetFamily(unsigned int family);
    void SetInitPos(const float3& pos);
    void SetInitQuat(const float4& q);
    void SetMass(float mass);  // makes the mesh a free body (unless its family prescribes motion)
    void SetMOI(const float3& moi);
    void SetMaterial(const std::shared_ptr<DEMMaterial>& mat);
    // Moves the vertices so that `p` (in the mesh frame) becomes the mesh frame's origin.
    void TranslateFrame(const float3& p);

    size_t GetNumTriangles() const { return m_faces.size(); }
    size_t GetNumVertices() const { return m_vertices.size(); }
    const std::vector<float3>& GetVertices() const { return m_vertices; }
    const std::vector<int3>& GetFaces() const { return m_faces; }
    const std::shared_ptr<DEMMaterial>& GetMaterial() const { return m_material; }
    family_t GetFamily() const { return m_family; }
    float3 GetInitPos() const { return m_pos; }
    float4 GetInitQuat() const { return m_oriQ; }
    float GetMass() const { return m_mass; }
    float3 GetMOI() const { return m_moi; }
    bool IsFree() const { return m_free; }
    // Owner id in user order (after clumps and external objects); valid after Initialize.
    size_t GetOwnerID() const { return m_ownerID; }

  private:
    friend class DEMSolver;
    void checkNotInitialized(const char* call) const;
    std::vector<float3> m_vertices;
    std::vector<int3> m_faces;
    std::shared_ptr<DEMMaterial> m_material;
    family_t m_family = 0;
    float3 m_pos = make_float3(0.f);
    float4 m_oriQ = make_float4(0.f, 0.f, 0.f, 1.f);
    float m_mass = 1e10f;
    float3 m_moi = make_float3(1e10f);
    bool m_free = false;
    size_t m_ownerID = 0;
    bool m_initialized = false;
};

}  // namespace deme
