// Inspectors: reductions over all clumps, evaluated on demand.
#pragma once

#include <memory>
#include <string>

#include "Stress.h"
#include "VectorTypes.h"

namespace deme {

class Simulation;

// Kinds: "clump_max_z", "clump_min_z" (of clump centres), "clump_max_absv" (largest speed),
// "clump_kinetic_energy" (translational + rotational, summed), "clump_mass" (total mass of the
// clumps in the simulation now), "num_contacts"; and, over a box region [lo, hi], "stress": the
// volume-averaged stress of the grains whose centres lie in it (Stress.h), whose GetValue() is the
// mean normal stress (compression positive).
class DEMInspector {
  public:
    // An inspector outliving its solver says so (deme::Error) instead of reading freed memory.
    DEMInspector(std::weak_ptr<Simulation> sim, std::string kind);
    // A kind over a region (only "stress" takes one).
    DEMInspector(std::weak_ptr<Simulation> sim, std::string kind, const float3& lo, const float3& hi);
    double GetValue() const;
    // A "stress" inspector's tensor, contact and kinetic parts (deme::Error for other kinds).
    StressTensor GetStress() const;
    const std::string& GetKind() const { return m_kind; }

  private:
    const Simulation& live(const char* call) const;
    std::weak_ptr<Simulation> m_owner;
    Simulation* m_sim;
    std::string m_kind;
    float3 m_lo = make_float3(0.f), m_hi = make_float3(0.f);
};

}  // namespace deme
