#include <deme/Inspector.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <deme/Error.h>

#include "api/Validate.h"
#include "runtime/Simulation.h"
#include "runtime/StressMeasure.h"

namespace deme {

namespace {
const char* KINDS[] = {"clump_max_z", "clump_min_z", "clump_max_absv", "clump_kinetic_energy", "clump_mass",
                       "num_contacts"};
}

DEMInspector::DEMInspector(std::weak_ptr<Simulation> sim, std::string kind)
    : m_owner(std::move(sim)), m_sim(m_owner.lock().get()), m_kind(std::move(kind)) {
    if (m_kind == "stress")
        throwError("CreateInspector", "the \"stress\" inspector takes a region: CreateInspector(\"stress\", lo, hi)");
    if (std::find(std::begin(KINDS), std::end(KINDS), m_kind) == std::end(KINDS))
        throwError("CreateInspector", "unknown inspector \"" + m_kind +
                                          "\" (clump_max_z, clump_min_z, clump_max_absv, clump_kinetic_energy, "
                                          "clump_mass, num_contacts; stress over a region)");
}

DEMInspector::DEMInspector(std::weak_ptr<Simulation> sim, std::string kind, const float3& lo, const float3& hi)
    : m_owner(std::move(sim)), m_sim(m_owner.lock().get()), m_kind(std::move(kind)), m_lo(lo), m_hi(hi) {
    if (m_kind != "stress")
        throwError("CreateInspector", "\"" + m_kind + "\" takes no region (only \"stress\" does)");
    requireBox("CreateInspector", "the stress region", lo, hi);
}

const Simulation& DEMInspector::live(const char* call) const {
    if (m_owner.expired()) throwError(call, "the solver this inspector belongs to has been destroyed");
    if (!m_sim->initialized()) throwError(call, "the solver is not initialized yet");
    return *m_sim;
}

StressTensor DEMInspector::GetStress() const {
    const char* call = "DEMInspector::GetStress";
    if (m_kind != "stress") throwError(call, "\"" + m_kind + "\" is not a stress inspector");
    return measureStress(live(call).stateWithContacts(), to_double3(m_lo), to_double3(m_hi));
}

double DEMInspector::GetValue() const {
    live("DEMInspector::GetValue");
    if (m_kind == "stress") return GetStress().Pressure();
    const SimState& s = m_sim->state();
    const size_t n = s.numClumps;
    if (m_kind == "num_contacts") return (double)m_sim->numRealContacts();
    if (m_kind == "clump_max_z" || m_kind == "clump_min_z") {
        const bool isMax = m_kind == "clump_max_z";
        double v = isMax ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
        for (size_t o = 0; o < n; o++) {
            const double z = m_sim->ownerPos(o).z;
            v = isMax ? std::max(v, z) : std::min(v, z);
        }
        return v;
    }
    if (m_kind == "clump_max_absv") {
        double v = 0.0;
        for (size_t o = 0; o < n; o++) v = std::max(v, (double)length(s.owners.vel[o]));
        return v;
    }
    if (m_kind == "clump_mass") {  // of the clumps in the simulation now (see GetRemovedMass)
        double m = 0.0;
        for (size_t o = 0; o < n; o++) m += (double)m_sim->ownerMass(o);
        return m;
    }
    // clump_kinetic_energy: translational plus rotational (body frame, principal moments).
    double e = 0.0;
    for (size_t o = 0; o < n; o++) {
        const float3 v = s.owners.vel[o], w = s.owners.angVel[o];
        const float3 I = m_sim->ownerMOI(o);
        e += 0.5 * (double)m_sim->ownerMass(o) * (double)dot(v, v) +
             0.5 * ((double)I.x * w.x * w.x + (double)I.y * w.y * w.y + (double)I.z * w.z * w.z);
    }
    return e;
}

}  // namespace deme
