// Copies what an output file needs out of the simulation's state into an OutputFrame, on the
// calling thread and between steps (the writer thread then works on the copy alone). The state is
// read through Simulation::state(), which on the CUDA backend first brings the host copy up to date
// with the device. Columns and their order are those of README.md's "Output files".
#pragma once

#include <deme/VectorTypes.h>

#include "io/OutputFrame.h"

namespace deme {

class Simulation;

// One row per sphere in user order: X,Y,Z (points), r, then the SetOutputContent columns and the
// owner wildcards if enabled.
OutputFrame stageSphereFrame(const Simulation& sim);
// One row per clump: owner, X,Y,Z, Q, v, w (body frame), mass, family, owner wildcards.
OutputFrame stageClumpFrame(const Simulation& sim);
// One row per geometry pair in contact (or loaded at a distance): type, ids, point, force, normal, overlap.
OutputFrame stageContactFrame(const Simulation& sim);
// Every mesh triangle in its current pose: 3 points each, cell data owner.
OutputFrame stageMeshFrame(const Simulation& sim);
// The coarse-grained stress (runtime/StressMeasure.h) of a box split into n[0] x n[1] x n[2] cells,
// one row per cell (x fastest): the cell's centre (points), the stress tensor (9 components, Pa,
// compression positive), its contact and kinetic parts, the pressure and the grains in the cell.
OutputFrame stageStressFrame(const Simulation& sim, const double3& lo, const double3& hi, const unsigned int n[3],
                             const char* call);

// Contact type codes of the VTU "type" array (CSV: the labels).
enum ContactTypeCode : uint8_t { CONTACT_SS = 0, CONTACT_SA = 1, CONTACT_SM = 2 };

}  // namespace deme
