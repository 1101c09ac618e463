#include <deme/DEMSolver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "api/Expression.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "api/Validate.h"
#include "backend/cpu/Parallel.h"
#include "io/ClumpCsvReader.h"
#include "io/ObjReader.h"
#include "io/OutputWriters.h"
#include "runtime/Simulation.h"
#include "runtime/StatsReport.h"

namespace deme {

DEMSolver::DEMSolver() : m_scene(new Scene()), m_sim(new Simulation()) {}
DEMSolver::~DEMSolver() = default;

void DEMSolver::requireNotInitialized(const char* call) const {
    if (m_sim->initialized()) throwError(call, "must be called before Initialize()");
}
void DEMSolver::requireInitialized(const char* call) const {
    if (!m_sim->initialized()) throwError(call, "must be called after Initialize()");
}

// ---------------------------------------------------------------- messages and output
void DEMSolver::SetVerbosity(const std::string& level) {
    static const std::map<std::string, Verbosity> levels = {{"QUIET", Verbosity::QUIET},
                                                            {"ERROR", Verbosity::ERROR},
                                                            {"WARNING", Verbosity::WARNING},
                                                            {"INFO", Verbosity::INFO},
                                                            {"STEP_METRIC", Verbosity::STEP_METRIC}};
    const auto it = levels.find(level);
    if (it == levels.end())
        throwError("SetVerbosity", "unknown level \"" + level + "\" (QUIET, ERROR, WARNING, INFO, STEP_METRIC)");
    m_sim->settings.verbosity = it->second;
}

void DEMSolver::SetOutputFormat(const std::string& format) {
    if (format != "CSV") throwError("SetOutputFormat", "unsupported format \"" + format + "\" (CSV)");
}

void DEMSolver::SetOutputContent(const std::string& content) {
    std::vector<std::string> items;
    std::string cur;
    for (char ch : content + " ") {
        if (ch == ' ' || ch == '|' || ch == ',') {
            if (!cur.empty()) items.push_back(cur);
            cur.clear();
        } else {
            cur += ch;
        }
    }
    SetOutputContent(items);
}

void DEMSolver::SetOutputContent(const std::vector<std::string>& content) {
    Settings& s = m_sim->settings;
    for (const auto& c : content) {
        if (c == "XYZ")
            continue;  // always written
        else if (c == "ABSV")
            s.outAbsv = true;
        else if (c == "VEL")
            s.outVel = true;
        else if (c == "ANG_VEL")
            s.outAngVel = true;
        else if (c == "FAMILY")
            s.outFamily = true;
        else if (c == "OWNER")
            s.outOwner = true;
        else if (c == "MAT")
            s.outMat = true;
        else if (c == "QUAT")
            s.outQuat = true;
        else
            throwError("SetOutputContent",
                       "unknown content \"" + c + "\" (XYZ, ABSV, VEL, ANG_VEL, FAMILY, OWNER, MAT, QUAT)");
    }
}

// ---------------------------------------------------------------- materials
std::shared_ptr<DEMMaterial> DEMSolver::LoadMaterial(const std::map<std::string, double>& props) {
    const char* call = "LoadMaterial";
    requireNotInitialized(call);
    static const char* known[] = {"E", "nu", "CoR", "mu", "Crr"};
    static const char* required[] = {"E", "nu", "CoR", "mu"};
    for (const auto& kv : props) {
        if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return kv.first == k; }) ==
            std::end(known))
            throwError(call, "unknown material property \"" + kv.first + "\" (known: E, nu, CoR, mu, Crr)");
        requireFinite(call, kv.first.c_str(), kv.second);
    }
    for (const char* r : required)
        if (!props.count(r)) throwError(call, std::string("missing material property \"") + r + "\"");
    if (!(props.at("E") > 0.0)) throwError(call, "E must be positive");
    if (!(props.at("nu") >= 0.0 && props.at("nu") < 0.5)) throwError(call, "nu must be in [0, 0.5)");
    if (!(props.at("CoR") >= 0.0 && props.at("CoR") <= 1.0)) throwError(call, "CoR must be in [0, 1]");
    if (!(props.at("mu") >= 0.0)) throwError(call, "mu must be >= 0");
    std::map<std::string, double> full = props;
    if (!full.count("Crr")) full["Crr"] = 0.0;
    if (!(full.at("Crr") >= 0.0)) throwError(call, "Crr must be >= 0");
    if (m_scene->materials.size() >= MAX_MATERIALS)
        throwError(call, "at most " + std::to_string(MAX_MATERIALS) + " materials");
    auto mat = std::make_shared<DEMMaterial>(full, (unsigned int)m_scene->materials.size());
    m_scene->materials.push_back(mat);
    return mat;
}

void DEMSolver::SetMaterialPropertyPair(const std::string& name, const std::shared_ptr<DEMMaterial>& a,
                                        const std::shared_ptr<DEMMaterial>& b, double value) {
    const char* call = "SetMaterialPropertyPair";
    requireNotInitialized(call);
    if (name != "CoR" && name != "mu" && name != "Crr")
        throwError(call, "\"" + name + "\" is not a pairwise property (CoR, mu, Crr)");
    if (!a || !b) throwError(call, "material is null");
    requireFinite(call, "value", value);
    if (value < 0.0 || (name == "CoR" && value > 1.0)) throwError(call, "value out of range for " + name);
    const unsigned int ia = a->GetLoadOrder(), ib = b->GetLoadOrder();
    m_scene->pairProperties[{name, std::min(ia, ib), std::max(ia, ib)}] = value;
}

// ---------------------------------------------------------------- domain and boundaries
void DEMSolver::InstructBoxDomainDimension(float x, float y, float z) {
    const char* call = "InstructBoxDomainDimension";
    requireNotInitialized(call);
    requirePositive(call, "x", x);
    requirePositive(call, "y", y);
    requirePositive(call, "z", z);
    m_scene->hasDomain = true;
    m_scene->domainSize = make_float3(x, y, z);
    m_scene->domainLo = make_float3(-0.5f * x, -0.5f * y, -0.5f * z);
}

void DEMSolver::InstructBoxDomainDimension(const std::pair<float, float>& x, const std::pair<float, float>& y,
                                           const std::pair<float, float>& z) {
    const char* call = "InstructBoxDomainDimension";
    requireNotInitialized(call);
    for (const auto* r : {&x, &y, &z}) {
        requireFinite(call, "lower bound", r->first);
        requireFinite(call, "upper bound", r->second);
        if (!(r->second > r->first)) throwError(call, "each range needs upper > lower");
    }
    m_scene->hasDomain = true;
    m_scene->domainLo = make_float3(x.first, y.first, z.first);
    m_scene->domainSize = make_float3(x.second - x.first, y.second - y.first, z.second - z.first);
}

void DEMSolver::InstructBoxDomainBoundingBC(const std::string& type, const std::shared_ptr<DEMMaterial>& mat) {
    const char* call = "InstructBoxDomainBoundingBC";
    requireNotInitialized(call);
    if (type != "all" && type != "top_open" && type != "none")
        throwError(call, "unknown type \"" + type + "\" (all, top_open, none)");
    if (!m_scene->hasDomain) throwError(call, "call InstructBoxDomainDimension first");
    if (type == "none") return;
    if (!mat) throwError(call, "material is null");
    const float3 lo = m_scene->domainLo, hi = m_scene->domainLo + m_scene->domainSize;
    auto walls = AddExternalObject();
    walls->AddPlane(make_float3(lo.x, 0, 0), make_float3(1, 0, 0), mat);
    walls->AddPlane(make_float3(hi.x, 0, 0), make_float3(-1, 0, 0), mat);
    walls->AddPlane(make_float3(0, lo.y, 0), make_float3(0, 1, 0), mat);
    walls->AddPlane(make_float3(0, hi.y, 0), make_float3(0, -1, 0), mat);
    walls->AddPlane(make_float3(0, 0, lo.z), make_float3(0, 0, 1), mat);
    if (type == "all") walls->AddPlane(make_float3(0, 0, hi.z), make_float3(0, 0, -1), mat);
}

std::shared_ptr<DEMExternObj> DEMSolver::AddExternalObject() {
    requireNotInitialized("AddExternalObject");
    auto obj = std::make_shared<DEMExternObj>();
    m_scene->externObjs.push_back(obj);
    return obj;
}

std::shared_ptr<DEMExternObj> DEMSolver::AddBCPlane(const float3& pos, const float3& normal,
                                                    const std::shared_ptr<DEMMaterial>& mat) {
    requireNotInitialized("AddBCPlane");
    auto obj = AddExternalObject();
    obj->AddPlane(pos, normal, mat);
    return obj;
}

// ---------------------------------------------------------------- meshes
std::shared_ptr<DEMMeshConnected> DEMSolver::AddWavefrontMeshObject(const std::string& objFile,
                                                                   const std::shared_ptr<DEMMaterial>& mat) {
    const char* call = "AddWavefrontMeshObject";
    requireNotInitialized(call);
    if (!mat) throwError(call, "material is null");
    ObjMesh obj = readObj(objFile, call);
    return AddWavefrontMeshObject(DEMMeshConnected(std::move(obj.vertices), std::move(obj.faces), mat));
}

std::shared_ptr<DEMMeshConnected> DEMSolver::AddWavefrontMeshObject(const DEMMeshConnected& mesh) {
    const char* call = "AddWavefrontMeshObject";
    requireNotInitialized(call);
    if (!mesh.GetMaterial()) throwError(call, "the mesh has no material (SetMaterial)");
    if (mesh.GetNumTriangles() == 0) throwError(call, "the mesh has no triangles");
    auto m = std::make_shared<DEMMeshConnected>(mesh);
    m_scene->meshes.push_back(m);
    return m;
}

void DEMSolver::SetMeshOutputFormat(const std::string& format) {
    if (format != "VTK") throwError("SetMeshOutputFormat", "unsupported format \"" + format + "\" (VTK)");
}

void DEMSolver::WriteMeshFile(const std::string& path) const {
    requireInitialized("WriteMeshFile");
    writeMeshVtk(*m_sim, path);
}

// ---------------------------------------------------------------- clump templates and clumps
std::shared_ptr<DEMClumpTemplate> DEMSolver::LoadClumpType(float mass, const float3& moi, const std::string& csvFile,
                                                           const std::shared_ptr<DEMMaterial>& mat) {
    const ClumpSpheres cs = readClumpCsv(csvFile, "LoadClumpType");
    return LoadClumpType(mass, moi, cs.radii, cs.positions, mat);
}

std::shared_ptr<DEMClumpTemplate> DEMSolver::LoadClumpType(float mass, const float3& moi,
                                                           const std::vector<float>& radii,
                                                           const std::vector<float3>& positions,
                                                           const std::shared_ptr<DEMMaterial>& mat) {
    return LoadClumpType(mass, moi, radii, positions, std::vector<std::shared_ptr<DEMMaterial>>(radii.size(), mat));
}

std::shared_ptr<DEMClumpTemplate> DEMSolver::LoadClumpType(float mass, const float3& moi,
                                                           const std::vector<float>& radii,
                                                           const std::vector<float3>& positions,
                                                           const std::vector<std::shared_ptr<DEMMaterial>>& mats) {
    const char* call = "LoadClumpType";
    requireNotInitialized(call);
    requirePositive(call, "mass", mass);
    requirePositive3(call, "MOI", moi);
    if (radii.empty()) throwError(call, "a clump needs at least one sphere");
    if (positions.size() != radii.size() || mats.size() != radii.size())
        throwError(call, "got " + std::to_string(radii.size()) + " radii, " + std::to_string(positions.size()) +
                             " positions and " + std::to_string(mats.size()) + " materials; they must match");
    for (size_t i = 0; i < radii.size(); i++) {
        requirePositive(call, "sphere radius", radii[i]);
        requireFinite3(call, "sphere position", positions[i]);
        if (!mats[i]) throwError(call, "material of sphere " + std::to_string(i) + " is null");
    }
    auto t = std::make_shared<DEMClumpTemplate>();
    t->mass = mass;
    t->MOI = moi;
    t->radii = radii;
    t->relPos = positions;
    t->materials = mats;
    m_scene->templates.push_back(t);
    return t;
}

std::shared_ptr<DEMClumpTemplate> DEMSolver::LoadSphereType(float mass, float radius,
                                                            const std::shared_ptr<DEMMaterial>& mat) {
    const char* call = "LoadSphereType";
    requireNotInitialized(call);
    requirePositive(call, "radius", radius);
    requirePositive(call, "mass", mass);
    if (!mat) throwError(call, "material is null");
    const float moi = 0.4f * mass * radius * radius;
    requirePositive(call, "moment of inertia 0.4 m r^2", moi);
    return LoadClumpType(mass, make_float3(moi), std::vector<float>{radius}, std::vector<float3>{make_float3(0.f)},
                         mat);
}

std::shared_ptr<DEMClumpBatch> DEMSolver::AddClumps(const std::shared_ptr<DEMClumpTemplate>& type,
                                                    const std::vector<float3>& positions) {
    return AddClumps(std::vector<std::shared_ptr<DEMClumpTemplate>>(positions.size(), type), positions);
}

std::shared_ptr<DEMClumpBatch> DEMSolver::AddClumps(const std::vector<std::shared_ptr<DEMClumpTemplate>>& types,
                                                    const std::vector<float3>& positions) {
    const char* call = "AddClumps";
    requireNotInitialized(call);
    if (types.size() != positions.size())
        throwError(call, "got " + std::to_string(types.size()) + " templates for " + std::to_string(positions.size()) +
                             " positions");
    for (size_t i = 0; i < types.size(); i++) {
        if (!types[i]) throwError(call, "template of clump " + std::to_string(i) + " is null");
        if (!(types[i]->mass > 0.f) || types[i]->radii.empty())
            throwError(call, "template of clump " + std::to_string(i) + " has no mass or no spheres");
        requireFinite3(call, "clump position", positions[i]);
    }
    auto batch = std::make_shared<DEMClumpBatch>(types, positions);
    m_scene->batches.push_back(batch);
    return batch;
}

// ---------------------------------------------------------------- families
void DEMSolver::SetFamilyFixed(unsigned int family) {
    m_sim->families.motion(requireFamily("SetFamilyFixed", family)).fixed = true;
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
}

void DEMSolver::SetFamilyPrescribedAngVel(unsigned int family, const std::string& wx, const std::string& wy,
                                          const std::string& wz) {
    const std::string e[3] = {wx, wy, wz};
    setPrescription(m_sim->families.motion(requireFamily("SetFamilyPrescribedAngVel", family)), true, e,
                    "SetFamilyPrescribedAngVel");
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
        for (auto& fam : m_sim->state().owners.family)
            if (fam == f) fam = t;
        m_sim->invalidateContacts();
        return;
    }
    for (auto& b : m_scene->batches) {
        std::vector<unsigned int> fams(b->GetFamilies().begin(), b->GetFamilies().end());
        for (auto& x : fams)
            if (x == f) x = t;
        b->SetFamily(fams);
    }
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
        m_sim.get(), [b]() { return b->GetOwnerOffset(); }, batch->GetNumClumps());
}

std::shared_ptr<DEMTracker> DEMSolver::Track(const std::shared_ptr<DEMExternObj>& obj) {
    if (!obj) throwError("Track", "object is null");
    if (std::find(m_scene->externObjs.begin(), m_scene->externObjs.end(), obj) == m_scene->externObjs.end())
        throwError("Track", "the object was not added to this solver");
    DEMExternObj* o = obj.get();
    return std::make_shared<DEMTracker>(
        m_sim.get(), [o]() { return o->GetOwnerID(); }, 1);
}

std::shared_ptr<DEMTracker> DEMSolver::Track(const std::shared_ptr<DEMMeshConnected>& mesh) {
    if (!mesh) throwError("Track", "mesh is null");
    if (std::find(m_scene->meshes.begin(), m_scene->meshes.end(), mesh) == m_scene->meshes.end())
        throwError("Track", "the mesh was not added to this solver");
    DEMMeshConnected* m = mesh.get();
    return std::make_shared<DEMTracker>(m_sim.get(), [m]() { return m->GetOwnerID(); }, 1);
}

std::shared_ptr<DEMInspector> DEMSolver::CreateInspector(const std::string& kind) {
    return std::make_shared<DEMInspector>(m_sim.get(), kind);
}

// ---------------------------------------------------------------- time stepping
void DEMSolver::SetInitTimeStep(double dt) {
    requirePositive("SetInitTimeStep", "time step", dt);
    m_sim->settings.dt = dt;
}
void DEMSolver::SetGravitationalAcceleration(const float3& g) {
    requireFinite3("SetGravitationalAcceleration", "gravity", g);
    m_sim->settings.gravity = g;
}
void DEMSolver::SetErrorOutVelocity(float v) {
    requirePositive("SetErrorOutVelocity", "velocity", v);
    m_sim->settings.errorOutVelocity = v;
}
void DEMSolver::SetMaxVelocity(float v) {
    requirePositive("SetMaxVelocity", "velocity", v);
    m_sim->settings.maxVelocity = v;
}
void DEMSolver::SetExpandSafetyMultiplier(float m) {
    if (!(m >= 1.f) || !std::isfinite(m)) throwError("SetExpandSafetyMultiplier", "multiplier must be >= 1");
    m_sim->settings.safetyMultiplier = m;
}
void DEMSolver::SetExpandSafetyAdder(float a) {
    if (!(a >= 0.f) || !std::isfinite(a)) throwError("SetExpandSafetyAdder", "adder must be >= 0");
    m_sim->settings.safetyAdder = a;
}
void DEMSolver::SetCDUpdateFreq(unsigned int n) {
    requireNotInitialized("SetCDUpdateFreq");
    if (n == 0) throwError("SetCDUpdateFreq", "update frequency must be at least 1");
    m_sim->settings.updateFreq = n;
}
void DEMSolver::SetCDMaxUpdateFreq(unsigned int n) {
    requireNotInitialized("SetCDMaxUpdateFreq");
    if (n == 0) throwError("SetCDMaxUpdateFreq", "the maximum update frequency must be at least 1");
    m_sim->settings.maxUpdateFreq = n;
}
void DEMSolver::UseAdaptiveUpdateFreq() {
    requireNotInitialized("UseAdaptiveUpdateFreq");
    m_sim->settings.adaptiveUpdateFreq = true;
}
void DEMSolver::DisableAdaptiveUpdateFreq() {
    requireNotInitialized("DisableAdaptiveUpdateFreq");
    m_sim->settings.adaptiveUpdateFreq = false;
}
unsigned int DEMSolver::GetUpdateFreq() const {
    return m_sim->initialized() ? m_sim->contactSets().nMax() : m_sim->settings.updateFreq;
}
void DEMSolver::SetSynchronousContactDetection(bool sync) {
    m_sim->settings.detectionMode = sync ? Settings::DetectionMode::SYNC : Settings::DetectionMode::ASYNC;
    if (m_sim->initialized()) m_sim->applyDetectionMode();
}
bool DEMSolver::UsesAsyncContactDetection() const { return m_sim->settings.asyncDetection; }

void DEMSolver::SetFamilyExtraMargin(unsigned int family, float margin) {
    const char* call = "SetFamilyExtraMargin";
    const family_t f = requireFamily(call, family);
    if (!(margin >= 0.f) || !std::isfinite(margin)) throwError(call, "extra margin must be >= 0 and finite");
    m_sim->settings.familyExtraMargin[f] = margin;
    m_sim->invalidateContacts();
}

void DEMSolver::SetInitBinSize(double size) {
    requireNotInitialized("SetInitBinSize");
    requirePositive("SetInitBinSize", "bin size", size);
    m_sim->settings.binSize = size;
}
void DEMSolver::SetForceCalcThreadsPerBlock(unsigned int n) {
    if (n == 0 || n > 1024) throwError("SetForceCalcThreadsPerBlock", "must be in 1..1024");
    m_sim->settings.threadsPerBlock = n;
}
void DEMSolver::SetCPUThreads(unsigned int n) {
    if (n == 0) throwError("SetCPUThreads", "need at least one thread");
    m_sim->settings.cpuThreads = n;
#ifdef _OPENMP
    omp_set_num_threads((int)n);
#endif
}

void DEMSolver::Initialize() {
    const char* call = "Initialize";
    requireNotInitialized(call);
    if (!(m_sim->settings.dt > 0.0)) throwError(call, "no time step: call SetInitTimeStep first");
    SimState state = assembleScene(*m_scene);
    size_t offset = 0;
    for (auto& b : m_scene->batches) {
        b->m_ownerOffset = offset;
        b->m_initialized = true;
        offset += b->GetNumClumps();
        for (auto& t : b->GetTypes()) t->m_frozen = true;
    }
    for (auto& o : m_scene->externObjs) {
        o->m_ownerID = offset++;
        o->m_initialized = true;
    }
    for (auto& m : m_scene->meshes) {
        m->m_ownerID = offset++;
        m->m_initialized = true;
    }
    m_sim->start(std::move(state));
}

void DEMSolver::DoDynamics(double duration) {
    const char* call = "DoDynamics";
    requireInitialized(call);
    if (!(duration >= 0.0) || !std::isfinite(duration)) throwError(call, "duration must be >= 0 and finite");
    // Steps to the nearest whole step, so that repeated frames do not drift.
    const double dt = m_sim->settings.dt;
    const double steps = std::floor(duration / dt + 0.5);
    if (steps > 1e15)
        throwError(call,
                   "duration " + std::to_string(duration) + " s is too many steps of " + std::to_string(dt) + " s");
    m_sim->advance((unsigned long long)steps);
}

void DEMSolver::DoDynamicsThenSync(double duration) {
    DoDynamics(duration);
    m_sim->syncContactDetection();
}

void DEMSolver::DoStepDynamics() {
    requireInitialized("DoStepDynamics");
    m_sim->advance(1);
}

// ---------------------------------------------------------------- queries
double DEMSolver::GetSimTime() const { return m_sim->time(); }
double DEMSolver::GetTimeStep() const { return m_sim->settings.dt; }
size_t DEMSolver::GetNumClumps() const {
    return m_sim->initialized() ? m_sim->state().numClumps : m_scene->numClumps();
}
size_t DEMSolver::GetNumSpheres() const {
    if (m_sim->initialized()) return m_sim->state().spheres.size();
    size_t n = 0;
    for (const auto& b : m_scene->batches)
        for (const auto& t : b->GetTypes()) n += t->GetNumSpheres();
    return n;
}
size_t DEMSolver::GetNumContacts() const { return m_sim->numRealContacts(); }
double DEMSolver::GetAvgSphContacts() const {
    const size_t nS = m_sim->state().spheres.size();
    if (nS == 0) return 0.0;
    const size_t ss = m_sim->numSphereSphereContacts();
    return (double)(2 * ss + (m_sim->numRealContacts() - ss)) / (double)nS;
}
float3 DEMSolver::GetGravitationalAcceleration() const { return m_sim->settings.gravity; }

// ---------------------------------------------------------------- output
void DEMSolver::WriteSphereFile(const std::string& path) const {
    requireInitialized("WriteSphereFile");
    writeSphereCsv(*m_sim, path);
}
void DEMSolver::WriteClumpFile(const std::string& path) const {
    requireInitialized("WriteClumpFile");
    writeClumpCsv(*m_sim, path);
}
void DEMSolver::WriteContactFile(const std::string& path) const {
    requireInitialized("WriteContactFile");
    writeContactCsv(*m_sim, path);
}

void DEMSolver::ShowTimingStats() const { std::cout << timingReport(*m_sim) << std::endl; }

void DEMSolver::ShowThreadCollaborationStats() const { std::cout << collaborationReport(*m_sim) << std::endl; }

}  // namespace deme
