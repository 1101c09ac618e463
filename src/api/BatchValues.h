// A batch's initial values clump by clump, without making the per-clump list of a value its clumps
// share (DEMClumpBatch keeps one value then): what scene assembly and the solver's pre-Initialize
// edits read and change.
#pragma once

#include <deme/ClumpTemplate.h>

namespace deme {

struct BatchValues {
    // Clump i's value of `v`: its own, or the one all share.
    template <class T>
    static const T& at(const std::vector<T>& v, size_t i) {
        return v.size() == 1 ? v[0] : v[i];
    }
    static const float3& vel(const DEMClumpBatch& b, size_t i) { return at(b.m_vel, i); }
    static const float3& angVel(const DEMClumpBatch& b, size_t i) { return at(b.m_angVel, i); }
    static const float4& oriQ(const DEMClumpBatch& b, size_t i) { return at(b.m_oriQ, i); }
    static family_t family(const DEMClumpBatch& b, size_t i) { return at(b.m_family, i); }
    // Every clump of family `from` in family `to` (ChangeFamily before Initialize).
    static void renameFamily(DEMClumpBatch& b, family_t from, family_t to) {
        for (family_t& f : b.m_family)
            if (f == from) f = to;
    }
};

}  // namespace deme
