// DEMSolver: family rules, trackers and inspectors.
#include <deme/DEMSolver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "codegen/Expression.h"
#include "api/BatchValues.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "api/Validate.h"
#include "parallel/Parallel.h"
#include "io/ClumpCsvReader.h"
#include "io/ObjReader.h"
#include "runtime/Simulation.h"
#include "runtime/StatsReport.h"

namespace deme {

// ---------------------------------------------------------------- families
void DEMSolver::SetFamilyFixed(unsigned int family) {
    m_sim->families.motion(requireFamily("SetFamilyFixed", family)).fixed = true;
    // After Initialize: detection learns which families are dormant or move (docs/active-box.md).
    if (m_sim->initialized()) m_sim->invalidateContacts();
}

namespace {

// Parses all three components before storing any, so a bad expression changes nothing.
void setPrescription(FamilyMotion& m, bool angular, const std::string* exprs, const char* call) {
    Expression parsed[3];
    for (int i = 0; i < 3; i++)
        if (exprs[i] != "none") parsed[i] = Expression::parse(exprs[i], {"t"}, call);
    for (int i = 0; i < 3; i++) {
        (angular ? m.angPrescribed : m.linPrescribed)[i] = exprs[i] != "none";
        (angular ? m.ang : m.lin)[i] = parsed[i];
    }
}

}  // namespace

void DEMSolver::SetFamilyPrescribedLinVel(unsigned int family, const std::string& vx, const std::string& vy,
                                          const std::string& vz) {
    const std::string e[3] = {vx, vy, vz};
    setPrescription(m_sim->families.motion(requireFamily("SetFamilyPrescribedLinVel", family)), false, e,
                    "SetFamilyPrescribedLinVel");
    if (m_sim->initialized()) m_sim->invalidateContacts();
}

void DEMSolver::SetFamilyPrescribedAngVel(unsigned int family, const std::string& wx, const std::string& wy,
                                          const std::string& wz) {
    const std::string e[3] = {wx, wy, wz};
    setPrescription(m_sim->families.motion(requireFamily("SetFamilyPrescribedAngVel", family)), true, e,
                    "SetFamilyPrescribedAngVel");
    if (m_sim->initialized()) m_sim->invalidateContacts();
}

void DEMSolver::DisableContactBetweenFamilies(unsigned int a, unsigned int b) {
    m_sim->families.setContact(requireFamily("DisableContactBetweenFamilies", a),
                               requireFamily("DisableContactBetweenFamilies", b), false);
    m_sim->invalidateContacts();
}

void DEMSolver::EnableContactBetweenFamilies(unsigned int a, unsigned int b) {
    m_sim->families.setContact(requireFamily("EnableContactBetweenFamilies", a),
                               requireFamily("EnableContactBetweenFamilies", b), true);
    m_sim->invalidateContacts();
}

void DEMSolver::ChangeFamily(unsigned int from, unsigned int to) {
    const family_t f = requireFamily("ChangeFamily", from), t = requireFamily("ChangeFamily", to);
    if (m_sim->initialized()) {
        for (auto& fam : m_sim->editState().owners.family)
            if (fam == f) fam = t;
        m_sim->invalidateContacts();
        return;
    }
    for (auto& b : m_scene->batches) BatchValues::renameFamily(*b, f, t);
    for (auto& o : m_scene->externObjs)
        if (o->GetFamily() == f) o->SetFamily(t);
}

// ---------------------------------------------------------------- trackers and inspectors
std::shared_ptr<DEMTracker> DEMSolver::Track(const std::shared_ptr<DEMClumpBatch>& batch) {
    if (!batch) throwError("Track", "batch is null");
    if (std::find(m_scene->batches.begin(), m_scene->batches.end(), batch) == m_scene->batches.end())
        throwError("Track", "the batch was not added to this solver");
    DEMClumpBatch* b = batch.get();
    return std::make_shared<DEMTracker>(
        m_sim, [b]() { return b->GetOwnerOffset(); }, batch->GetNumClumps());
}

std::shared_ptr<DEMTracker> DEMSolver::Track(const std::shared_ptr<DEMExternObj>& obj) {
    if (!obj) throwError("Track", "object is null");
    if (std::find(m_scene->externObjs.begin(), m_scene->externObjs.end(), obj) == m_scene->externObjs.end())
        throwError("Track", "the object was not added to this solver");
    DEMExternObj* o = obj.get();
    return std::make_shared<DEMTracker>(
        m_sim, [o]() { return o->GetOwnerID(); }, 1);
}

std::shared_ptr<DEMTracker> DEMSolver::Track(const std::shared_ptr<DEMMeshConnected>& mesh) {
    if (!mesh) throwError("Track", "mesh is null");
    if (std::find(m_scene->meshes.begin(), m_scene->meshes.end(), mesh) == m_scene->meshes.end())
        throwError("Track", "the mesh was not added to this solver");
    DEMMeshConnected* m = mesh.get();
    return std::make_shared<DEMTracker>(
        m_sim, [m]() { return m->GetOwnerID(); }, 1);
}

std::shared_ptr<DEMInspector> DEMSolver::CreateInspector(const std::string& kind) {
    return std::make_shared<DEMInspector>(m_sim, kind);
}

std::shared_ptr<DEMInspector> DEMSolver::CreateInspector(const std::string& kind, const float3& lo, const float3& hi) {
    return std::make_shared<DEMInspector>(m_sim, kind, lo, hi);
}

}  // namespace deme
