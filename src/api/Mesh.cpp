#include <deme/Mesh.h>

#include "api/Validate.h"

namespace deme {

DEMMeshConnected::DEMMeshConnected(std::vector<float3> vertices, std::vector<int3> faces,
                                   std::shared_ptr<DEMMaterial> mat)
    : m_vertices(std::move(vertices)), m_faces(std::move(faces)), m_material(std::move(mat)) {
    const char* call = "DEMMeshConnected";
    for (const auto& v : m_vertices) requireFinite3(call, "vertex", v);
    const int n = (int)m_vertices.size();
    for (size_t i = 0; i < m_faces.size(); i++) {
        const int3 f = m_faces[i];
        if (f.x < 0 || f.y < 0 || f.z < 0 || f.x >= n || f.y >= n || f.z >= n)
            throwError(call, "face " + std::to_string(i) + " indexes a vertex outside 0.." + std::to_string(n - 1));
    }
}

void DEMMeshConnected::checkNotInitialized(const char* call) const {
    if (m_initialized) throwError(call, "the mesh is already initialized; use a tracker to move it");
}

void DEMMeshConnected::Scale(float s) { Scale(make_float3(s, s, s)); }

void DEMMeshConnected::Scale(const float3& s) {
    const char* call = "DEMMeshConnected::Scale";
    checkNotInitialized(call);
    requirePositive3(call, "scale factors", s);
    for (auto& v : m_vertices) v = v * s;
}

void DEMMeshConnected::SetFamily(unsigned int family) {
    checkNotInitialized("DEMMeshConnected::SetFamily");
    m_family = requireFamily("DEMMeshConnected::SetFamily", family);
}
void DEMMeshConnected::SetInitPos(const float3& pos) {
    checkNotInitialized("DEMMeshConnected::SetInitPos");
    requireFinite3("DEMMeshConnected::SetInitPos", "position", pos);
    m_pos = pos;
}
void DEMMeshConnected::SetInitQuat(const float4& q) {
    checkNotInitialized("DEMMeshConnected::SetInitQuat");
    m_oriQ = requireQuaternion("DEMMeshConnected::SetInitQuat", q);
}
void DEMMeshConnected::SetMass(float mass) {
    checkNotInitialized("DEMMeshConnected::SetMass");
    requirePositive("DEMMeshConnected::SetMass", "mass", mass);
    m_mass = mass;
    m_free = true;
}
void DEMMeshConnected::SetMOI(const float3& moi) {
    checkNotInitialized("DEMMeshConnected::SetMOI");
    requirePositive3("DEMMeshConnected::SetMOI", "MOI", moi);
    m_moi = moi;
}
void DEMMeshConnected::SetMaterial(const std::shared_ptr<DEMMaterial>& mat) {
    checkNotInitialized("DEMMeshConnected::SetMaterial");
    if (!mat) throwError("DEMMeshConnected::SetMaterial", "material is null");
    m_material = mat;
}
void DEMMeshConnected::TranslateFrame(const float3& p) {
    checkNotInitialized("DEMMeshConnected::TranslateFrame");
    requireFinite3("DEMMeshConnected::TranslateFrame", "point", p);
    for (auto& v : m_vertices) v = v - p;
}

}  // namespace deme
