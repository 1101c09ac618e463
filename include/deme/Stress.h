// The volume-averaged stress of the grains in a region (docs/periodic.md, "Stress"), from
// DEMInspector::GetStress() of a "stress" inspector. Pa, compression positive; row-major:
// sigma[3 * i + j] is the ij component (x = 0, y = 1, z = 2).
//
//   contact part: sigma_ij = -(1 / V) sum over grains p in the region, over the contacts c of p, of
//                 a_i f_j, with a the arm from p's centre to the contact point and f the contact
//                 force on p (for a pair pressed together: + F l / V, F the force, l the distance
//                 between the centres)
//   kinetic part: sigma_ij = (1 / V) sum over grains p in the region of m_p u_i u_j, with u the
//                 grain's velocity less the region's mass-weighted mean velocity
//
// A grain belongs to the region that holds its centre; walls and meshes are not grains (their side
// of a contact does not count). Per-contact forces are those of the last step.
#pragma once

#include <array>
#include <cstddef>

namespace deme {

struct StressTensor {
    std::array<double, 9> total{}, contact{}, kinetic{};
    double volume = 0.0;   // of the region, m^3
    size_t grains = 0;     // grains (clumps) whose centre lies in it
    size_t contacts = 0;   // contacts of those grains with a force
    // Mean normal stress (trace / 3), compression positive.
    double Pressure() const { return (total[0] + total[4] + total[8]) / 3.0; }
};

}  // namespace deme
