#include <deme/ClumpTemplate.h>

#include <algorithm>
#include <string>
#include <unordered_map>

#include "api/Validate.h"
#include "runtime/MemoryAccounting.h"

namespace deme {

void DEMClumpTemplate::Scale(float s) {
    requirePositive("DEMClumpTemplate::Scale", "scale factor", s);
    if (m_frozen) throwError("DEMClumpTemplate::Scale", "the template is in use by an initialized simulation");
    for (auto& r : radii) r *= s;
    for (auto& p : relPos) p = p * s;
    mass *= s * s * s;
    MOI = MOI * (s * s * s * s * s);
}

float DEMClumpTemplate::GetExtent() const {
    float e = 0.f;
    for (size_t i = 0; i < radii.size(); i++) e = std::max(e, length(relPos[i]) + radii[i]);
    return e;
}

DEMClumpBatch::DEMClumpBatch(std::shared_ptr<DEMClumpTemplate> type, std::vector<float3> positions)
    : m_pos(std::move(positions)),
      m_vel(1, make_float3(0.f)),  // one value each, which every clump takes until set one by one
      m_angVel(1, make_float3(0.f)),
      m_oriQ(1, make_float4(0.f, 0.f, 0.f, 1.f)),
      m_family(1, 0),
      m_numClumps(m_pos.size()) {
    if (type) m_distinctTypes.push_back(std::move(type));
}

DEMClumpBatch::DEMClumpBatch(std::vector<std::shared_ptr<DEMClumpTemplate>> types, std::vector<float3> positions)
    : DEMClumpBatch(std::shared_ptr<DEMClumpTemplate>(), std::move(positions)) {
    if (types.size() != m_numClumps)
        throwError("DEMClumpBatch", "got " + std::to_string(types.size()) + " templates for " +
                                        std::to_string(m_numClumps) + " positions");
    // A 16-byte pointer per clump would outweigh much of what the solver keeps per clump: the
    // templates once each, and an index per clump only where they differ.
    std::unordered_map<const DEMClumpTemplate*, uint32_t> index;
    std::vector<uint32_t> perClump(types.size());
    for (size_t i = 0; i < types.size(); i++) {
        auto [it, added] = index.try_emplace(types[i].get(), (uint32_t)index.size());
        if (added) m_distinctTypes.push_back(types[i]);
        perClump[i] = it->second;
    }
    if (m_distinctTypes.size() > 1) m_typeIndex = std::move(perClump);
}

const std::shared_ptr<DEMClumpTemplate>& DEMClumpBatch::GetType(size_t i) const {
    if (i >= m_numClumps || m_distinctTypes.empty())
        throwError("DEMClumpBatch::GetType", "clump " + std::to_string(i) + " of a batch of " +
                                                 std::to_string(m_numClumps) + " clumps" +
                                                 (m_distinctTypes.empty() ? " without a template" : ""));
    return m_distinctTypes[m_typeIndex.empty() ? 0 : m_typeIndex[i]];
}

std::vector<std::shared_ptr<DEMClumpTemplate>> DEMClumpBatch::GetTypes() const {
    std::vector<std::shared_ptr<DEMClumpTemplate>> out;
    out.reserve(m_numClumps);
    for (size_t i = 0; i < m_numClumps; i++) out.push_back(GetType(i));
    return out;
}

namespace {

// `values` as one per clump: a single shared value is made into the list here, for the caller who
// asks for the list.
template <class T>
const std::vector<T>& perClump(std::vector<T>& values, size_t n) {
    if (values.size() != n) {
        const T shared = values.front();
        values.assign(n, shared);
    }
    return values;
}

}  // namespace

template <class T>
T& DEMClumpBatch::initialValues(T& values, const char* call) const {
    if (m_initialized)
        throwError(call, "the batch's clumps are in the solver's state since Initialize (or UpdateClumps); read "
                         "and steer them with a tracker");
    return values;
}

void DEMClumpBatch::handOver() {
    m_initialized = true;
    releaseVector(m_pos);
    releaseVector(m_vel);
    releaseVector(m_angVel);
    releaseVector(m_oriQ);
    releaseVector(m_family);
}

size_t DEMClumpBatch::GetHostBytes() const {
    return vectorBytes(m_pos) + vectorBytes(m_vel) + vectorBytes(m_angVel) + vectorBytes(m_oriQ) +
           vectorBytes(m_family) + vectorBytes(m_typeIndex) + vectorBytes(m_distinctTypes);
}

const std::vector<float3>& DEMClumpBatch::GetPositions() const {
    return initialValues(m_pos, "DEMClumpBatch::GetPositions");
}
const std::vector<float3>& DEMClumpBatch::GetVelocities() const {
    return perClump(initialValues(m_vel, "DEMClumpBatch::GetVelocities"), m_numClumps);
}
const std::vector<float3>& DEMClumpBatch::GetAngVelocities() const {
    return perClump(initialValues(m_angVel, "DEMClumpBatch::GetAngVelocities"), m_numClumps);
}
const std::vector<float4>& DEMClumpBatch::GetOriQs() const {
    return perClump(initialValues(m_oriQ, "DEMClumpBatch::GetOriQs"), m_numClumps);
}
const std::vector<family_t>& DEMClumpBatch::GetFamilies() const {
    return perClump(initialValues(m_family, "DEMClumpBatch::GetFamilies"), m_numClumps);
}

namespace {

void requireNotHandedOver(bool initialized, const char* call) {
    if (initialized) throwError(call, "the batch is already initialized; use a tracker to change running clumps");
}

template <typename T>
void assignPerClump(std::vector<T>& dst, const std::vector<T>& src, size_t n, bool initialized, const char* call) {
    requireNotHandedOver(initialized, call);
    if (src.size() != n)
        throwError(call, "got " + std::to_string(src.size()) + " values for " + std::to_string(n) + " clumps");
    dst = src;
}

}  // namespace

// One value for every clump is kept once (the getters make the list where asked).
void DEMClumpBatch::SetVel(const float3& v) {
    requireNotHandedOver(m_initialized, "DEMClumpBatch::SetVel");
    requireFinite3("DEMClumpBatch::SetVel", "velocity", v);
    m_vel.assign(1, v);
}
void DEMClumpBatch::SetVel(const std::vector<float3>& v) {
    for (const auto& x : v) requireFinite3("DEMClumpBatch::SetVel", "velocity", x);
    assignPerClump(m_vel, v, m_numClumps, m_initialized, "DEMClumpBatch::SetVel");
}
void DEMClumpBatch::SetAngVel(const float3& w) {
    requireNotHandedOver(m_initialized, "DEMClumpBatch::SetAngVel");
    requireFinite3("DEMClumpBatch::SetAngVel", "angular velocity", w);
    m_angVel.assign(1, w);
}
void DEMClumpBatch::SetAngVel(const std::vector<float3>& w) {
    for (const auto& x : w) requireFinite3("DEMClumpBatch::SetAngVel", "angular velocity", x);
    assignPerClump(m_angVel, w, m_numClumps, m_initialized, "DEMClumpBatch::SetAngVel");
}
void DEMClumpBatch::SetOriQ(const float4& q) {
    requireNotHandedOver(m_initialized, "DEMClumpBatch::SetOriQ");
    m_oriQ.assign(1, requireQuaternion("DEMClumpBatch::SetOriQ", q));
}
void DEMClumpBatch::SetOriQ(const std::vector<float4>& q) {
    std::vector<float4> normalized;
    normalized.reserve(q.size());
    for (const auto& x : q) normalized.push_back(requireQuaternion("DEMClumpBatch::SetOriQ", x));
    assignPerClump(m_oriQ, normalized, m_numClumps, m_initialized, "DEMClumpBatch::SetOriQ");
}
void DEMClumpBatch::SetFamily(unsigned int family) {
    requireNotHandedOver(m_initialized, "DEMClumpBatch::SetFamily");
    m_family.assign(1, requireFamily("DEMClumpBatch::SetFamily", family));
}
void DEMClumpBatch::SetFamily(const std::vector<unsigned int>& families) {
    std::vector<family_t> f;
    f.reserve(families.size());
    for (unsigned int x : families) f.push_back(requireFamily("DEMClumpBatch::SetFamily", x));
    assignPerClump(m_family, f, m_numClumps, m_initialized, "DEMClumpBatch::SetFamily");
}

}  // namespace deme
