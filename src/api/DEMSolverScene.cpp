// DEMSolver: materials, domain, boundaries, meshes, clump templates and clumps (before Initialize).
#include <deme/DEMSolver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "codegen/Expression.h"
#include "api/Scene.h"
#include "api/SceneAssembly.h"
#include "api/Validate.h"
#include "parallel/Parallel.h"
#include "forcemodel/Identifiers.h"
#include "io/ClumpCsvReader.h"
#include "io/ObjReader.h"
#include "io/OutputManager.h"
#include "runtime/Simulation.h"
#include "runtime/StatsReport.h"

namespace deme {

// ---------------------------------------------------------------- materials
std::shared_ptr<DEMMaterial> DEMSolver::LoadMaterial(const std::map<std::string, double>& props) {
    const char* call = "LoadMaterial";
    requireNotInitialized(call);
    // Any property a force model may read by name; the ones the model needs are checked at Initialize.
    for (const auto& kv : props) {
        if (!isCppIdentifier(kv.first))
            throwError(call, "material property \"" + kv.first +
                                 "\" is not a C++ identifier (force models read properties by name)");
        requireFinite(call, kv.first.c_str(), kv.second);
    }
    // The standard properties' ranges, where given.
    auto has = [&](const char* k) { return props.count(k) > 0; };
    if (has("E") && !(props.at("E") > 0.0)) throwError(call, "E must be positive");
    if (has("nu") && !(props.at("nu") >= 0.0 && props.at("nu") < 0.5)) throwError(call, "nu must be in [0, 0.5)");
    if (has("CoR") && !(props.at("CoR") >= 0.0 && props.at("CoR") <= 1.0)) throwError(call, "CoR must be in [0, 1]");
    if (has("mu") && !(props.at("mu") >= 0.0)) throwError(call, "mu must be >= 0");
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
    // Whether the force model reads `name` per pair is checked at Initialize.
    if (!isCppIdentifier(name)) throwError(call, "\"" + name + "\" is not a C++ identifier");
    if (!a || !b) throwError(call, "material is null");
    requireFinite(call, "value", value);
    if ((name == "CoR" || name == "mu" || name == "Crr") && (value < 0.0 || (name == "CoR" && value > 1.0)))
        throwError(call, "value out of range for " + name);
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

void DEMSolver::InstructBoxDomainPeriodicity(const std::string& axes) {
    const char* call = "InstructBoxDomainPeriodicity";
    requireNotInitialized(call);
    unsigned int bits = 0;
    for (char c : axes) {
        const int a = c == 'x' || c == 'X' ? 0 : c == 'y' || c == 'Y' ? 1 : c == 'z' || c == 'Z' ? 2 : -1;
        if (a < 0) throwError(call, "\"" + axes + "\": axes are named by x, y and z (e.g. \"xy\"; \"\" for none)");
        if (bits & (1u << a)) throwError(call, "\"" + axes + "\" names an axis twice");
        bits |= 1u << a;
    }
    m_scene->periodicAxes = bits;
}

void DEMSolver::SetPeriodicShear(double rate) {
    const char* call = "SetPeriodicShear";
    requireNotInitialized(call);
    if (!std::isfinite(rate)) throwError(call, "the shear rate must be finite, got " + std::to_string(rate));
    m_scene->sheared = true;
    m_scene->shearRate = rate;
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
    if (format != "VTK" && format != "VTU")
        throwError("SetMeshOutputFormat", "unsupported format \"" + format + "\" (VTK, VTU)");
    m_output->options.meshVtu = format == "VTU";
}

void DEMSolver::WriteMeshFile(const std::string& path) const {
    requireInitialized("WriteMeshFile");
    m_output->write(OutputKind::MESHES, *m_sim, path, "WriteMeshFile");
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
    const char* call = "LoadClumpType";  // also after Initialize, for clumps added during a run
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
    requirePositive(call, "radius", radius);
    requirePositive(call, "mass", mass);
    if (!mat) throwError(call, "material is null");
    const float moi = 0.4f * mass * radius * radius;
    requirePositive(call, "moment of inertia 0.4 m r^2", moi);
    return LoadClumpType(mass, make_float3(moi), std::vector<float>{radius}, std::vector<float3>{make_float3(0.f)},
                         mat);
}

namespace {

void requireUsableTemplate(const char* call, const std::shared_ptr<DEMClumpTemplate>& t, const std::string& which) {
    if (!t) throwError(call, which + " is null");
    if (!(t->mass > 0.f) || t->radii.empty()) throwError(call, which + " has no mass or no spheres");
}

}  // namespace

std::shared_ptr<DEMClumpBatch> DEMSolver::AddClumps(const std::shared_ptr<DEMClumpTemplate>& type,
                                                    const std::vector<float3>& positions) {
    const char* call = "AddClumps";
    requireUsableTemplate(call, type, "the template");
    for (const float3& p : positions) requireFinite3(call, "clump position", p);
    return addClumpBatch(std::make_shared<DEMClumpBatch>(type, positions), call);
}

std::shared_ptr<DEMClumpBatch> DEMSolver::AddClumps(const std::vector<std::shared_ptr<DEMClumpTemplate>>& types,
                                                    const std::vector<float3>& positions) {
    const char* call = "AddClumps";
    if (types.size() != positions.size())
        throwError(call, "got " + std::to_string(types.size()) + " templates for " + std::to_string(positions.size()) +
                             " positions");
    for (size_t i = 0; i < types.size(); i++) {
        requireUsableTemplate(call, types[i], "template of clump " + std::to_string(i));
        requireFinite3(call, "clump position", positions[i]);
    }
    return addClumpBatch(std::make_shared<DEMClumpBatch>(types, positions), call);
}

std::shared_ptr<DEMClumpBatch> DEMSolver::addClumpBatch(std::shared_ptr<DEMClumpBatch> batch, const char* call) {
    if (m_sim->initialized()) addClumpsDuringRun(batch, call);  // api/DEMSolverSceneChanges.cpp
    m_scene->batches.push_back(batch);
    return batch;
}

}  // namespace deme
