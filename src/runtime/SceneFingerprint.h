// What identifies the scene a script set up before Initialize(), so that a checkpoint is read only
// into the scene it was written from (io/Checkpoint.h). Taken once, when the simulation starts, and
// kept: a checkpoint records the fingerprint of its run's initial scene, whatever was added,
// removed or changed since, and a restarted run (the same script up to Initialize) compares its
// own initial fingerprint with it. The state arrays themselves come from the checkpoint.
#pragma once

#include <cstdint>
#include <string>

#include "forcemodel/ModelLayout.h"
#include "state/SimState.h"

namespace deme {

struct SceneFingerprint {
    // Counts, compared one by one so that a mismatch can say what differs.
    uint64_t owners = 0, clumps = 0, analyticalOwners = 0, spheres = 0, analytical = 0, triangles = 0;
    uint64_t templates = 0;  // mass property entries (one per clump template, external object, mesh)
    uint64_t materials = 0, families = 0;  // families: distinct family numbers in use at Initialize
    uint64_t contactWildcards = 0, ownerWildcards = 0, geometryWildcards = 0;
    // FNV-1a hashes of what the script gave: every INPUT field of the owners, templates and
    // geometries (state/StateFields.h), the material tables, the domain, and the force model.
    uint64_t ownerInputs = 0, templateInputs = 0, geometryInputs = 0, materialInputs = 0, domain = 0, model = 0;
};

// The fingerprint of `s` as assembled by Initialize (before any step or edit).
SceneFingerprint sceneFingerprint(const SimState& s, const ModelLayout& model);

// FNV-1a's state `h` after `count` zero bytes: each xors nothing in and multiplies by the prime, so
// the run is one multiplication by the prime's count-th power (mod 2^64), taken by squaring: what
// the byte loop gives, in log(count) steps (the offsets a layout without them stands for).
uint64_t fnv1aAfterZeroBytes(uint64_t h, uint64_t count);

// Empty if `checkpoint` and `mine` are the same scene; otherwise what differs first, e.g.
// "1200 spheres in the checkpoint's scene, 1100 in this one".
std::string fingerprintMismatch(const SceneFingerprint& checkpoint, const SceneFingerprint& mine);

// The fields of SceneFingerprint in a fixed order, with names (for the file format and messages):
// f(name, value, isCount); the others are hashes.
template <class F>
void forEachFingerprintField(SceneFingerprint& fp, F&& f) {
    f("owners", fp.owners, true);
    f("clumps", fp.clumps, true);
    f("analytical owners", fp.analyticalOwners, true);
    f("spheres", fp.spheres, true);
    f("analytical components", fp.analytical, true);
    f("triangles", fp.triangles, true);
    f("clump templates and mass properties", fp.templates, true);
    f("materials", fp.materials, true);
    f("families in use", fp.families, true);
    f("contact wildcards", fp.contactWildcards, true);
    f("owner wildcards", fp.ownerWildcards, true);
    f("geometry wildcards", fp.geometryWildcards, true);
    f("owners' inputs (families, types, templates, sizes)", fp.ownerInputs, false);
    f("clump templates' masses and moments of inertia", fp.templateInputs, false);
    f("geometries (sphere radii and positions, analytical components, triangles, materials)", fp.geometryInputs, false);
    f("material properties", fp.materialInputs, false);
    f("domain", fp.domain, false);
    f("force model", fp.model, false);
}

}  // namespace deme
