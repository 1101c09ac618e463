// DEMSolver: scenes that change while they run -- clumps added and removed between DoDynamics calls,
// and the domain exit policy (docs/scene-changes.md). The edits of the state are
// runtime/SceneEdits.h's; this file checks the user's input and keeps the batches' bookkeeping.
#include <deme/DEMSolver.h>

#include <cmath>

#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "api/Validate.h"
#include "runtime/Simulation.h"
#include "runtime/TextFormat.h"

namespace deme {

// A batch added after Initialize: checked now (the domain and the materials are known), inserted by
// UpdateClumps. Its user ids are fixed now: after every id issued so far and the batches waiting.
void DEMSolver::addClumpsDuringRun(const std::shared_ptr<DEMClumpBatch>& batch, const char* call) {
    const Scene& sc = *m_scene;
    const float3 lo = sc.domainLo, hi = sc.domainLo + sc.domainSize;
    for (size_t i = 0; i < batch->GetNumClumps(); i++) {
        const float3 p = batch->GetPositions()[i];
        if (!(p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z))
            throwError(call, "clump " + std::to_string(i) + " of the batch at " + formatVector(p) +
                                 " is outside the simulation domain (from " + formatVector(lo) + " to " + formatVector(hi) + ")");
        for (const auto& m : batch->GetType(i)->materials) {
            const unsigned int k = m ? m->GetLoadOrder() : 0;
            if (!m || k >= sc.materials.size() || sc.materials[k] != m)
                throwError(call, "a template of clump " + std::to_string(i) +
                                     " uses a material not loaded by this solver before Initialize");
        }
    }
    size_t offset = m_sim->state().ownerUserToInternal.size();
    for (const auto& b : sc.pendingBatches) offset += b->GetNumClumps();
    batch->m_ownerOffset = offset;
    m_scene->pendingBatches.push_back(batch);
}

void DEMSolver::UpdateClumps() {
    const char* call = "UpdateClumps";
    requireInitialized(call);
    if (m_scene->pendingBatches.empty()) return;
    // The waiting batches are assembled as a scene of their own in the same domain (the same frame,
    // the same layout of the force model), then merged into the running state.
    Scene part;
    part.materials = m_scene->materials;
    part.hasDomain = true;
    part.domainLo = m_scene->domainLo;
    part.domainSize = m_scene->domainSize;
    part.periodicAxes = m_scene->periodicAxes;
    part.batches = m_scene->pendingBatches;
    const SimState rows = assembleScene(part, m_sim->forceModel(), false);  // (the full arrays insertClumps reads)
    m_sim->insertClumps(rows);
    for (auto& b : m_scene->pendingBatches) {
        for (auto& t : b->GetDistinctTypes()) t->m_frozen = true;
        b->handOver();
    }
    m_scene->pendingBatches.clear();
}

size_t DEMSolver::RemoveClumpsInFamily(unsigned int family) {
    const char* call = "RemoveClumpsInFamily";
    requireInitialized(call);
    const family_t f = requireFamily(call, family);
    const SimState& s = m_sim->state();
    std::vector<uint8_t> remove(s.owners.size(), 0);
    for (size_t o = 0; o < s.numClumps; o++) remove[o] = s.owners.family[o] == f ? 1 : 0;
    return m_sim->removeClumps(remove);
}

void DEMSolver::SetDomainExitPolicy(const std::string& policy) {
    if (policy != "error" && policy != "remove")
        throwError("SetDomainExitPolicy", "unknown policy \"" + policy + "\" (error, remove)");
    m_sim->settings.removeLeavingClumps = policy == "remove";
}

size_t DEMSolver::GetNumRemovedClumps() const { return m_sim->initialized() ? m_sim->state().numRemovedClumps : 0; }

double DEMSolver::GetRemovedMass() const { return m_sim->initialized() ? m_sim->state().removedMass : 0.0; }

}  // namespace deme
