// Inspectors: reductions over all clumps, evaluated on demand.
#pragma once

#include <memory>
#include <string>

namespace deme {

class Simulation;

// Kinds: "clump_max_z", "clump_min_z" (of clump centres), "clump_max_absv" (largest speed),
// "clump_kinetic_energy" (translational + rotational, summed), "clump_mass" (total mass of the
// clumps in the simulation now), "num_contacts".
class DEMInspector {
  public:
    // An inspector outliving its solver says so (deme::Error) instead of reading freed memory.
    DEMInspector(std::weak_ptr<Simulation> sim, std::string kind);
    double GetValue() const;
    const std::string& GetKind() const { return m_kind; }

  private:
    std::weak_ptr<Simulation> m_owner;
    Simulation* m_sim;
    std::string m_kind;
};

}  // namespace deme
