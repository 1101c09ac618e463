// Checkpoint and restart (docs/checkpoint.md): everything a run needs to go on, written to one file
// and read back into a solver that a new process built from the same script up to Initialize().
// On the CPU the restarted run is bit for bit the run that was not interrupted.
//
// What is written: the state arrays of state/StateFields.h (every EVOLVES, RESULT and INPUT field of the
// owners, mass properties, geometries and the contact set with its wildcards and persistence marks;
// by name, so a field added to the lists is included without further code), the host tables beside
// them (id maps, per-owner geometry ranges, owner and geometry wildcards, contact wildcard rules),
// the clock and step counter, what n_max has adapted to, the run settings that may change after
// Initialize (step size, gravity, margins), the family rules, and the fingerprint of the scene as
// Initialize assembled it, and the kinematic cache (derived, but recomputing it may round otherwise).
// What is not: the steps' scratch and the CPU's contact bookkeeping (rebuilt at the next detection),
// materials and the domain (the script's, checked through the fingerprint).
#pragma once

#include <string>

namespace deme {

class Simulation;

// Writes the simulation's current state to `path` (temporary name, then rename: a crash leaves
// the previous file of that name intact). Does not change the run in any way.
void writeCheckpoint(const Simulation& sim, const std::string& path, const std::string& call);

// Reads `path` into `sim`, which must have been initialized from the same scene. Throws deme::Error
// naming the call and the file if the file is not a checkpoint, is truncated, corrupted (checksum),
// of another format version or state layout, or of another scene; then `sim` is left as it was.
void readCheckpoint(Simulation& sim, const std::string& path, const std::string& call);

}  // namespace deme
