// Materials: named properties, loaded through DEMSolver::LoadMaterial.
#pragma once

#include <map>
#include <string>

namespace deme {

// A handle to a loaded material. Properties are the ones given to LoadMaterial; the default force
// model reads E, nu, CoR, mu and Crr (Crr defaults to 0).
class DEMMaterial {
  public:
    DEMMaterial(std::map<std::string, double> props, unsigned int id) : m_props(std::move(props)), m_id(id) {}
    const std::map<std::string, double>& GetProperties() const { return m_props; }
    double Get(const std::string& name) const { return m_props.at(name); }
    // Position of this material in load order; the force model's bodyAMatType/bodyBMatType.
    unsigned int GetLoadOrder() const { return m_id; }

  private:
    std::map<std::string, double> m_props;
    unsigned int m_id;
};

}  // namespace deme
