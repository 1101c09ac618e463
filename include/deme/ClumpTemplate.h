// Clump templates (an element shape made of spheres, with its mass properties) and batches of
// clump instances added to a simulation.
#pragma once

#include <memory>
#include <vector>

#include "Materials.h"
#include "VariableTypes.h"

namespace deme {

// Component sphere positions are in the clump's principal frame, relative to its centre of mass;
// MOI holds the principal moments of inertia about that frame's axes.
class DEMClumpTemplate {
  public:
    float mass = 0.f;
    float3 MOI = make_float3(0.f);
    std::vector<float> radii;
    std::vector<float3> relPos;
    std::vector<std::shared_ptr<DEMMaterial>> materials;  // one per component sphere

    // Scales geometry by s, mass by s^3 and MOI by s^5 (constant density). s > 0.
    void Scale(float s);
    size_t GetNumSpheres() const { return radii.size(); }
    // Largest distance from the centre to any point of the component spheres.
    float GetExtent() const;

  private:
    friend class DEMSolver;
    bool m_frozen = false;  // set at Initialize: a template in use can no longer change
};

// Clumps added by one AddClumps call. Setters take one value for all clumps or one per clump.
// At Initialize (or UpdateClumps) the solver takes the batch's clumps into its own state and the
// batch lets go of its per-clump arrays of initial values (docs/memory.md): from then on their
// getters are errors, and a tracker reads and steers the running clumps. The templates stay.
class DEMClumpBatch {
  public:
    DEMClumpBatch(std::vector<std::shared_ptr<DEMClumpTemplate>> types, std::vector<float3> positions);
    // Every clump of one template.
    DEMClumpBatch(std::shared_ptr<DEMClumpTemplate> type, std::vector<float3> positions);

    size_t GetNumClumps() const { return m_numClumps; }
    void SetVel(const float3& v);
    void SetVel(const std::vector<float3>& v);
    void SetAngVel(const float3& w);  // local frame
    void SetAngVel(const std::vector<float3>& w);
    void SetOriQ(const float4& q);
    void SetOriQ(const std::vector<float4>& q);
    void SetFamily(unsigned int family);
    void SetFamily(const std::vector<unsigned int>& families);

    // The template of each clump, as a new list (the batch keeps one index per clump, none where
    // all its clumps share one template: docs/memory.md).
    std::vector<std::shared_ptr<DEMClumpTemplate>> GetTypes() const;
    // Clump i's template (i < GetNumClumps()).
    const std::shared_ptr<DEMClumpTemplate>& GetType(size_t i) const;
    // The templates the batch uses, each once, in the order of their first clump.
    const std::vector<std::shared_ptr<DEMClumpTemplate>>& GetDistinctTypes() const { return m_distinctTypes; }
    const std::vector<float3>& GetPositions() const;
    const std::vector<float3>& GetVelocities() const;
    const std::vector<float3>& GetAngVelocities() const;
    const std::vector<float4>& GetOriQs() const;
    const std::vector<family_t>& GetFamilies() const;
    // Index of the batch's first clump among all owners; valid after Initialize.
    size_t GetOwnerOffset() const { return m_ownerOffset; }
    // Host bytes of the batch's own arrays: its initial values until Initialize (or UpdateClumps),
    // then only its templates and their per-clump index (counted in GetMemoryStats' owner state).
    size_t GetHostBytes() const;

  private:
    friend class DEMSolver;
    friend struct BatchValues;  // reads a clump's value without making the list (src/api/BatchValues.h)
    std::vector<std::shared_ptr<DEMClumpTemplate>> m_distinctTypes;
    std::vector<uint32_t> m_typeIndex;  // per clump, into m_distinctTypes; empty if there is one
    std::vector<float3> m_pos;
    // One value per clump, or a single one every clump takes (the defaults, or a Set call with one
    // value: 41 of a clump's 53 bytes of initial values never made); a getter makes the list.
    mutable std::vector<float3> m_vel, m_angVel;
    mutable std::vector<float4> m_oriQ;
    mutable std::vector<family_t> m_family;
    size_t m_numClumps = 0;
    size_t m_ownerOffset = 0;
    bool m_initialized = false;
    // Marks the batch initialized and frees its per-clump arrays (the solver's state holds them).
    void handOver();
    // `values`, or a deme::Error naming `call` once the batch was handed over.
    template <class T>
    T& initialValues(T& values, const char* call) const;
};

}  // namespace deme
