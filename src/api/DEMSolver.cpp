#include <deme/DEMSolver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <unistd.h>

#include "codegen/Expression.h"
#include "api/Scene.h"
#include "api/ForceModelSetup.h"
#include "api/SceneAssembly.h"
#include "api/Validate.h"
#include "parallel/Parallel.h"
#include "io/ClumpCsvReader.h"
#include "io/ObjReader.h"
#include "io/OutputManager.h"
#include "io/ProgressReporter.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/BackendSelection.h"
#include "runtime/AllocatorPolicy.h"
#include "runtime/ContactEdits.h"
#include "runtime/Simulation.h"
#include "runtime/StatsReport.h"

namespace deme {

namespace {

// Wildcard values given before Initialize (SetFamilyOwnerWildcardValue, SetFamilyContactWildcardInitValue),
// now that the model's names are known; an unknown name is an error naming the call that gave it.
void applyWildcardValuesGivenEarly(const Scene& scene, const ModelLayout& layout, SimState& s) {
    for (const auto& v : scene.familyOwnerWildcards) {
        const int w = indexOf(layout.ownerWildcards, v.name);
        if (w < 0)
            throwError("SetFamilyOwnerWildcardValue", "the force model has no owner wildcard \"" + v.name +
                                                          "\" (declare it with SetPerOwnerWildcards)");
        for (size_t o = 0; o < s.owners.size(); o++)
            if (s.owners.family[o] == v.family) s.wildcards.owner[w][o] = v.value;
    }
    for (const auto& v : scene.contactWildcardInits) {
        const int w = indexOf(layout.contactWildcards, v.name);
        if (w < 0)
            throwError("SetFamilyContactWildcardInitValue", "the force model has no contact wildcard \"" + v.name +
                                                                "\" (declare it with SetPerContactWildcards)");
        addContactWildcardInit(s.wildcards, {v.a, v.b, (unsigned int)w, v.value});
    }
}

}  // namespace

DEMSolver::DEMSolver()
    : m_scene(new Scene()), m_sim(new Simulation()), m_output(new OutputManager()),
      m_progress(new ProgressReporter(std::cout, ::isatty(STDOUT_FILENO) == 1)) {
    fixLargeBlockBound();
    attachProgressHooks();
}
DEMSolver::DEMSolver(unsigned int nGPUs) : DEMSolver() {
    if (nGPUs == 0) throwError("DEMSolver", "the number of GPUs must be at least 1");
    for (unsigned int i = 0; i < nGPUs; i++) m_sim->settings.deviceIds.push_back((int)i);
}
DEMSolver::DEMSolver(const std::vector<int>& deviceIds) : DEMSolver() {
    if (deviceIds.empty()) throwError("DEMSolver", "the list of GPU ids is empty");
    for (int id : deviceIds)
        if (id < 0) throwError("DEMSolver", "GPU id " + std::to_string(id) + " is negative");
    m_sim->settings.deviceIds = deviceIds;
}
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

// The format settings take effect with the next output call: a file already handed to the writer
// thread is written as it was staged.
void DEMSolver::SetOutputFormat(const std::string& format) {
    if (format != "CSV" && format != "VTU")
        throwError("SetOutputFormat", "unsupported format \"" + format + "\" (CSV, VTU)");
    m_output->options.vtu = format == "VTU";
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

void DEMSolver::SetOutputContent(std::initializer_list<std::string> content) {
    SetOutputContent(std::vector<std::string>(content));
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

// ---------------------------------------------------------------- time stepping
void DEMSolver::SetInitTimeStep(double dt) {
    requirePositive("SetInitTimeStep", "time step", dt);
    m_sim->settings.dt = dt;
}
void DEMSolver::UpdateStepSize(double dt) {
    requirePositive("UpdateStepSize", "time step", dt);
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
    return m_sim->initialized() ? m_sim->updateFreq() : m_sim->settings.updateFreq;
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
    if (!m_scene->forceModel)
        m_scene->forceModel = std::make_shared<DEMForceModel>(DEMForceModel::Kind::FRICTIONAL_HERTZIAN);
    const ModelLayout layout = resolveModelLayout(*m_scene->forceModel, *m_scene, call);
    SimState state = assembleScene(*m_scene, layout);
    applyWildcardValuesGivenEarly(*m_scene, layout, state);
    // The backend is chosen and a custom model compiled for it here (or found in the cache). A
    // failure to start (a model the compiler rejects, no usable GPU for SetBackend("cuda")) leaves the
    // solver as it was: the scene's objects are marked initialized only once the simulation runs, so
    // the user may fix the cause and call Initialize again.
    m_sim->start(std::move(state), layout);
    m_scene->forceModel->m_locked = true;
    size_t offset = 0;
    for (auto& b : m_scene->batches) {
        b->m_ownerOffset = offset;
        offset += b->GetNumClumps();
        for (auto& t : b->GetDistinctTypes()) t->m_frozen = true;
        b->handOver();
    }
    for (auto& o : m_scene->externObjs) {
        o->m_ownerID = offset++;
        o->m_initialized = true;
    }
    for (auto& m : m_scene->meshes) {
        m->m_ownerID = offset++;
        m->m_initialized = true;
    }
}

void DEMSolver::DoDynamics(double duration) {
    const char* call = "DoDynamics";
    requireInitialized(call);
    if (!m_scene->pendingBatches.empty()) throwError(call, "clumps added by AddClumps wait for UpdateClumps()");
    if (!(duration >= 0.0) || !std::isfinite(duration)) throwError(call, "duration must be >= 0 and finite");
    // Steps to the nearest whole step, so that repeated frames do not drift.
    const double dt = m_sim->settings.dt;
    const double steps = std::floor(duration / dt + 0.5);
    if (steps > 1e15)
        throwError(call,
                   "duration " + std::to_string(duration) + " s is too many steps of " + std::to_string(dt) + " s");
    m_sim->advance((unsigned long long)steps);
    rethrowCallbackError();
}

void DEMSolver::DoDynamicsThenSync(double duration) {
    DoDynamics(duration);
    m_sim->syncContactDetection();
}

void DEMSolver::DoStepDynamics() {
    requireInitialized("DoStepDynamics");
    if (!m_scene->pendingBatches.empty())
        throwError("DoStepDynamics", "clumps added by AddClumps wait for UpdateClumps()");
    m_sim->advance(1);
    rethrowCallbackError();
}

void DEMSolver::SetInterruptCheck(std::function<bool()> check) {
    RunMonitor& monitor = m_sim->monitor();
    if (m_interruptHook >= 0) monitor.removeHook(m_interruptHook);
    m_interruptHook = -1;
    if (check) m_interruptHook = monitor.addHook([check](const RunProgress& p) { return !p.finished && check(); });
}

bool DEMSolver::WasInterrupted() const { return m_sim->monitor().stopped(); }

// ---------------------------------------------------------------- queries
double DEMSolver::GetSimTime() const { return m_sim->time(); }
double DEMSolver::GetTimeStep() const { return m_sim->settings.dt; }
size_t DEMSolver::GetNumClumps() const {
    return m_sim->initialized() ? m_sim->numClumps() : m_scene->numClumps();
}
size_t DEMSolver::GetNumSpheres() const {
    if (m_sim->initialized()) return m_sim->numSpheres();
    size_t n = 0;
    for (const auto& b : m_scene->batches)
        for (size_t i = 0; i < b->GetNumClumps(); i++) n += b->GetType(i)->GetNumSpheres();
    return n;
}
size_t DEMSolver::GetNumContacts() const { return m_sim->numRealContacts(); }
double DEMSolver::GetAvgSphContacts() const {
    const size_t nS = m_sim->numSpheres();
    if (nS == 0) return 0.0;
    const size_t ss = m_sim->numSphereSphereContacts();
    return (double)(2 * ss + (m_sim->numRealContacts() - ss)) / (double)nS;
}
float3 DEMSolver::GetGravitationalAcceleration() const { return m_sim->settings.gravity; }

// ---------------------------------------------------------------- output
void DEMSolver::WriteSphereFile(const std::string& path) const {
    requireInitialized("WriteSphereFile");
    m_output->write(OutputKind::SPHERES, *m_sim, path, "WriteSphereFile");
}
void DEMSolver::WriteClumpFile(const std::string& path) const {
    requireInitialized("WriteClumpFile");
    m_output->write(OutputKind::CLUMPS, *m_sim, path, "WriteClumpFile");
}
void DEMSolver::WriteStressField(const std::string& path, const float3& lo, const float3& hi, unsigned int nx,
                                 unsigned int ny, unsigned int nz) const {
    const char* call = "WriteStressField";
    requireInitialized(call);
    requireBox(call, "the box", lo, hi);
    if (nx == 0 || ny == 0 || nz == 0) throwError(call, "each axis needs at least one cell");
    if ((double)nx * ny * nz > 1e8) throwError(call, "more than 10^8 cells");
    const unsigned int n[3] = {nx, ny, nz};
    m_output->writeStressField(*m_sim, path, to_double3(lo), to_double3(hi), n, call);
}

void DEMSolver::WriteContactFile(const std::string& path) const {
    requireInitialized("WriteContactFile");
    m_output->write(OutputKind::CONTACTS, *m_sim, path, "WriteContactFile");
}

void DEMSolver::ShowTimingStats() const { std::cout << timingReport(*m_sim) << std::endl; }

void DEMSolver::SetBackend(const std::string& backend) {
    requireNotInitialized("SetBackend");
    parseBackendRequest("SetBackend", backend);  // validates
    m_sim->settings.backend = backend;
}

std::string DEMSolver::GetBackend() const {
    requireInitialized("GetBackend");
    return m_sim->settings.onGpu ? "cuda" : "cpu";
}

size_t DEMSolver::GetDeviceMemUsage() const { return m_sim->settings.onGpu ? cuda::deviceBytesAllocated() : 0; }

void DEMSolver::ShowMemStats() const {
    std::cout << "[deme] memory: " << (m_sim->settings.onGpu ? "GPU " : "CPU backend, GPU ")
              << (double)cuda::deviceBytesAllocated() / (1 << 20) << " MiB held now, "
              << (double)cuda::deviceBytesAllocatedPeak() / (1 << 20) << " MiB at most";
    // Dynamics and kinematics on two GPUs: what each holds.
    const std::vector<int>& ids = m_sim->settings.deviceIds;
    if (m_sim->settings.onGpu && ids.size() > 1)
        for (size_t i = 0; i < 2; i++)
            std::cout << (i == 0 ? " (GPU " : ", GPU ") << ids[i] << ": "
                      << (double)cuda::deviceBytesAllocatedOn(ids[i]) / (1 << 20) << " MiB" << (i == 1 ? ")" : "");
    if (m_sim->initialized() && m_sim->settings.onGpu && m_sim->numSpheres())
        std::cout << " (" << (double)cuda::deviceBytesAllocated() / (double)m_sim->numSpheres()
                  << " bytes per sphere)";
    std::cout << std::endl;
}

MemoryStats DEMSolver::GetMemoryStats() const {
    requireInitialized("GetMemoryStats");
    MemoryStats m = m_sim->hostMemory();
    m.hostBytes[(int)MemoryGroup::OUTPUT] += m_output->stagedBytes();
    // The batches the scene keeps: their template indices, and the initial values of those waiting
    // for UpdateClumps (docs/memory.md).
    for (const auto& b : m_scene->batches) m.hostBytes[(int)MemoryGroup::OWNER_STATE] += b->GetHostBytes();
    if (m_sim->settings.onGpu)
        for (int g = 0; g < NUM_MEMORY_GROUPS; g++) {
            m.deviceBytes[g] = cuda::deviceBytesInGroup((MemoryGroup)g);
            m.devicePeakBytes[g] = cuda::deviceBytesInGroupAtPeak((MemoryGroup)g);
        }
    return m;
}

void DEMSolver::ShowMemoryStats() const {
    requireInitialized("ShowMemoryStats");
    std::cout << memoryReport(GetMemoryStats()) << std::endl;
}

void DEMSolver::ShowThreadCollaborationStats() const { std::cout << collaborationReport(*m_sim) << std::endl; }

void DEMSolver::ClearThreadCollaborationStats() { m_sim->clearCollaborationStats(); }

double DEMSolver::GetDynamicsWaitShare() const {
    const CollaborationStats& c = m_sim->contactSets().stats();
    return c.dynamicsSeconds > 0.0 ? std::min(1.0, c.dynamicsWaitSeconds / c.dynamicsSeconds) : 0.0;
}

unsigned long long DEMSolver::GetNumAsyncContactSetUpdates() const {
    const CollaborationStats& c = m_sim->contactSets().stats();
    return c.acsUpdates > c.syncDetections ? c.acsUpdates - c.syncDetections : 0;
}

}  // namespace deme
