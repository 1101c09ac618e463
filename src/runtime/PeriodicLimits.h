// What periodic boundaries (InstructBoxDomainPeriodicity, physics/Periodic.h) ask of a scene, and
// the largest contact margin they allow. Two geometries interact through their nearest images, so
// no interaction may reach half a period; analytical boundaries must be the same in every period
// (a plane parallel to each periodic axis, a cylinder along the periodic axis).
#pragma once

#include "kinematics/BinGrid.h"
#include "state/SimState.h"

namespace deme {

// Throws deme::Error naming `call` if the scene does not suit its periodic axes (none: nothing to
// check): a period under six times the largest sphere radius, a plane whose normal has a component
// along a periodic axis (a wall on a periodic face among them), or a cylinder not along one.
void checkPeriodicScene(const SimState& s, const char* call);
// The part of that check for spheres of `radii` (clumps inserted during a run).
void checkPeriodicRadii(const PeriodicBox& p, const std::vector<float>& radii, const char* call);

// A sheared cell (SetPeriodicShear) needs 6 bins or more along x.
void checkShearedGrid(const PeriodicBox& p, const BinGrid& g, const char* call);

// The largest margin detection may enlarge geometries by, so that the reach of any two spheres
// (radii plus twice the margin plus the families' extra margins) stays within 90 % of half the
// shortest period; unbounded without periodic axes. A cap costs only earlier re-detections: a set
// expires when an owner travels its margin.
double periodicMarginCap(const SimState& s, const float* familyExtraMargin);

}  // namespace deme
