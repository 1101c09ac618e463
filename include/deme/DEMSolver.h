// DEMSolver: the user's entry point, with the method names of the paper's listings (§4).
// A thin facade: each method validates its input and forwards to the scene description (before
// Initialize) or to the running simulation.
#pragma once

#include <exception>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ClumpTemplate.h"
#include "ExternalObject.h"
#include "ForceModel.h"
#include "Inspector.h"
#include "Materials.h"
#include "MemoryStats.h"
#include "Mesh.h"
#include "RunProgress.h"
#include "RunSummary.h"
#include "Snapshot.h"
#include "Tracker.h"
#include "VariableTypes.h"

namespace deme {

class Scene;
class Simulation;
class OutputManager;
class ProgressReporter;

class DEMSolver {
  public:
    DEMSolver();
    // The paper's forms: run on the first nGPUs GPUs, or on the GPUs with these ids (the backend is
    // still chosen as SetBackend says; with no usable GPU, "auto" runs on the CPU and says so).
    explicit DEMSolver(unsigned int nGPUs);
    explicit DEMSolver(const std::vector<int>& deviceIds);
    ~DEMSolver();
    DEMSolver(const DEMSolver&) = delete;
    DEMSolver& operator=(const DEMSolver&) = delete;

    // ---- Messages and output ----
    // "QUIET", "ERROR", "WARNING", "INFO", "STEP_METRIC" (each includes the ones before it).
    void SetVerbosity(const std::string& level);
    // Files of WriteSphereFile, WriteClumpFile and WriteContactFile: "CSV" (default) or "VTU" (VTK XML
    // unstructured grids that ParaView opens as they are; docs/paraview.md).
    void SetOutputFormat(const std::string& format);
    // VTU data: "appended" (raw binary after the XML, default: fastest) or "base64" (text inside the
    // XML); compression "none" (default) or "zlib" (smaller, slower; worth it on slow storage).
    void SetVTUEncoding(const std::string& encoding);
    void SetVTUCompression(const std::string& compression);
    // Extra sphere-file columns: "XYZ" (always written), "ABSV", "VEL", "ANG_VEL", "FAMILY", "OWNER",
    // "MAT", "QUAT". A single string may list several separated by spaces or '|'.
    void SetOutputContent(const std::string& content);
    void SetOutputContent(const std::vector<std::string>& content);
    // A brace list, as the paper writes it: SetOutputContent({"XYZ", "ABSV"}). Without this overload
    // a brace list of one name also makes a std::string (from the name), one of two names too (the
    // iterator-pair constructor), and the call is ambiguous; with it, every brace list is the list.
    void SetOutputContent(std::initializer_list<std::string> content);

    // ---- Materials ----
    // Properties by name (C++ identifiers). The default model reads E, nu, CoR, mu and Crr (Crr defaults
    // to 0); a custom model reads whatever it names. Which ones are required is checked at Initialize.
    std::shared_ptr<DEMMaterial> LoadMaterial(const std::map<std::string, double>& props);
    // Pairwise value of a property (e.g. CoR, mu, Crr) between two materials; otherwise the average.
    // The force model must read the property per pair (SetMustPairwiseMatProp; the default model:
    // CoR, mu, Crr).
    void SetMaterialPropertyPair(const std::string& name, const std::shared_ptr<DEMMaterial>& a,
                                 const std::shared_ptr<DEMMaterial>& b, double value);

    // ---- Contact force model (docs/force-models.md) ----
    // The model in use is the last one chosen before Initialize; by default the frictional Hertzian
    // (history-based Hertz-Mindlin) model. The built-in models are compiled into the library.
    std::shared_ptr<DEMForceModel> UseFrictionalHertzianModel();
    std::shared_ptr<DEMForceModel> UseFrictionlessHertzianModel();
    // A custom model: C++ statements run for every pair of the contact set, compiled at Initialize
    // (and cached). Declare its material properties and wildcards on the returned handle.
    std::shared_ptr<DEMForceModel> DefineContactForceModel(const std::string& code);
    std::shared_ptr<DEMForceModel> ReadContactForceModel(const std::string& path);

    // ---- Wildcards of the force model (ids in user order; after Initialize unless noted) ----
    void SetOwnerWildcardValue(const std::string& name, size_t ownerID, float value);
    // Owners firstOwnerID, firstOwnerID + 1, ... get values[0], values[1], ...
    void SetOwnerWildcardValue(const std::string& name, size_t firstOwnerID, const std::vector<float>& values);
    // Every owner of the family; before Initialize, applied to the family's owners by Initialize.
    void SetFamilyOwnerWildcardValue(unsigned int family, const std::string& name, float value);
    float GetOwnerWildcardValue(const std::string& name, size_t ownerID) const;
    std::vector<float> GetOwnerWildcardValue(const std::string& name, size_t firstOwnerID, size_t count) const;
    // Geometry wildcards of spheres (ids as in the sphere file), mesh triangles (index over all meshes
    // in the order added) and analytical components (index over all external objects' components).
    void SetSphereWildcardValue(const std::string& name, size_t sphereID, float value);
    void SetSphereWildcardValue(const std::string& name, size_t firstSphereID, const std::vector<float>& values);
    float GetSphereWildcardValue(const std::string& name, size_t sphereID) const;
    std::vector<float> GetSphereWildcardValue(const std::string& name, size_t firstSphereID, size_t count) const;
    void SetTriWildcardValue(const std::string& name, size_t triangleID, float value);
    float GetTriWildcardValue(const std::string& name, size_t triangleID) const;
    void SetAnalWildcardValue(const std::string& name, size_t componentID, float value);
    float GetAnalWildcardValue(const std::string& name, size_t componentID) const;
    // Contact wildcards of the contacts now in the set: all of them, those between families a and b,
    // those with either or both owners in a family. A one-time change (the paper's meaning).
    void SetContactWildcardValue(const std::string& name, float value);
    void SetFamilyContactWildcardValue(unsigned int a, unsigned int b, const std::string& name, float value);
    void SetFamilyContactWildcardValueEither(unsigned int family, const std::string& name, float value);
    void SetFamilyContactWildcardValueBoth(unsigned int family, const std::string& name, float value);
    // A rule: contacts that enter the set between families a and b from now on start with `value`
    // instead of 0 (before or after Initialize; a later rule for the same name and families wins).
    void SetFamilyContactWildcardInitValue(unsigned int a, unsigned int b, const std::string& name, float value);
    // Sphere and clump files get one column per owner wildcard, named as the wildcard.
    void EnableOwnerWildcardOutput(bool enable = true);

    // ---- Persistent contacts (after Initialize) ----
    // The pairs now in the contact set (touching or within the margin, see SetFamilyExtraMargin) stay
    // in it even when they separate, until the force model clears `persistent` or the user removes
    // them: all pairs, pairs between families a and b, pairs with either or both owners in a family.
    void MarkPersistentContact();
    void MarkFamilyPersistentContact(unsigned int a, unsigned int b);
    void MarkFamilyPersistentContactEither(unsigned int family);
    void MarkFamilyPersistentContactBoth(unsigned int family);
    void RemovePersistentContact();
    void RemoveFamilyPersistentContact(unsigned int a, unsigned int b);
    void RemoveFamilyPersistentContactEither(unsigned int family);
    void RemoveFamilyPersistentContactBoth(unsigned int family);
    size_t GetNumPersistentContacts() const;

    // ---- Domain and analytical boundaries ----
    // Box of size x * y * z centred on the origin; every grain must stay inside it.
    void InstructBoxDomainDimension(float x, float y, float z);
    // Box spanning [x.first, x.second] x [y.first, y.second] x [z.first, z.second].
    void InstructBoxDomainDimension(const std::pair<float, float>& x, const std::pair<float, float>& y,
                                    const std::pair<float, float>& z);
    // Walls on the domain's faces: "all", "top_open" (no +z wall) or "none".
    // Periodic boundaries: along each axis named ("x", "y", "z", or several, as "xy"; "" for none) the
    // domain's two faces are one. A grain leaving through one enters through the other with its
    // velocity, spin and contacts; geometries interact through their nearest images. Walls on a
    // periodic face, planes not parallel to a periodic axis and cylinders not along one are errors
    // at Initialize, as is a period under six times the largest sphere radius (docs/periodic.md).
    void InstructBoxDomainPeriodicity(const std::string& axes);
    // A sheared periodic cell (Lees–Edwards): simple shear at `rate` (1/s) along x with its gradient
    // along z, with no walls. The images across the z faces move at +-rate * Lz along x and are
    // displaced by rate * Lz * t (less whole periods), so a grain leaving through the top enters
    // through the bottom displaced and slower by rate * Lz. Needs periodic x and z; before
    // Initialize (docs/periodic.md).
    void SetPeriodicShear(double rate);
    void InstructBoxDomainBoundingBC(const std::string& type, const std::shared_ptr<DEMMaterial>& mat);
    std::shared_ptr<DEMExternObj> AddExternalObject();
    std::shared_ptr<DEMExternObj> AddBCPlane(const float3& pos, const float3& normal,
                                             const std::shared_ptr<DEMMaterial>& mat);

    // ---- Meshes ----
    // Loads a Wavefront OBJ file as one rigid mesh owner with one material.
    std::shared_ptr<DEMMeshConnected> AddWavefrontMeshObject(const std::string& objFile,
                                                             const std::shared_ptr<DEMMaterial>& mat);
    // Adds a mesh built in code (its material must be set).
    std::shared_ptr<DEMMeshConnected> AddWavefrontMeshObject(const DEMMeshConnected& mesh);
    // "VTK" (legacy ASCII, default) or "VTU" (as SetOutputFormat's, with its encoding options).
    void SetMeshOutputFormat(const std::string& format);
    // Every mesh in its current pose, as one file (cell data: owner id); written in the background
    // like the other output files (see WriteSphereFile).
    void WriteMeshFile(const std::string& path) const;

    // ---- Clump templates and clumps ----
    std::shared_ptr<DEMClumpTemplate> LoadClumpType(float mass, const float3& moi, const std::string& csvFile,
                                                    const std::shared_ptr<DEMMaterial>& mat);
    std::shared_ptr<DEMClumpTemplate> LoadClumpType(float mass, const float3& moi, const std::vector<float>& radii,
                                                    const std::vector<float3>& positions,
                                                    const std::shared_ptr<DEMMaterial>& mat);
    std::shared_ptr<DEMClumpTemplate> LoadClumpType(float mass, const float3& moi, const std::vector<float>& radii,
                                                    const std::vector<float3>& positions,
                                                    const std::vector<std::shared_ptr<DEMMaterial>>& mats);
    std::shared_ptr<DEMClumpTemplate> LoadSphereType(float mass, float radius, const std::shared_ptr<DEMMaterial>& mat);
    std::shared_ptr<DEMClumpBatch> AddClumps(const std::shared_ptr<DEMClumpTemplate>& type,
                                             const std::vector<float3>& positions);
    std::shared_ptr<DEMClumpBatch> AddClumps(const std::vector<std::shared_ptr<DEMClumpTemplate>>& types,
                                             const std::vector<float3>& positions);

    // ---- Scenes that change while they run (docs/scene-changes.md) ----
    // AddClumps after Initialize: the batch (checked at once: its clumps must lie inside the domain)
    // waits, and may still be given velocities and families, until UpdateClumps() puts every
    // waiting batch into the simulation between DoDynamics calls. New clumps get user ids after all
    // ids issued so far (GetOwnerOffset; Track works as for any batch); existing contacts keep their
    // history. DoDynamics with batches still waiting is an error. Templates may be loaded after
    // Initialize too, from the materials loaded before it.
    void UpdateClumps();
    // Removes every clump of the family now (between calls) with its spheres and contacts; returns
    // how many. The ids of the others do not change; a removed clump's tracker rows say so.
    size_t RemoveClumpsInFamily(unsigned int family);
    // What happens to a clump that leaves the domain: "error" (default) stops the run naming it;
    // "remove" takes it out of the run at the step it leaves (parked on the device, its contacts
    // gone; removed from the state by the end of the DoDynamics call), and the run goes on.
    void SetDomainExitPolicy(const std::string& policy);
    // Clumps removed since Initialize (RemoveClumpsInFamily and the "remove" exit policy), and their
    // total mass.
    size_t GetNumRemovedClumps() const;
    double GetRemovedMass() const;

    // ---- Families (tags 0..255) ----
    void SetFamilyFixed(unsigned int family);
    // Each string is an expression of the simulation time t, or "none" to leave that component free.
    void SetFamilyPrescribedLinVel(unsigned int family, const std::string& vx, const std::string& vy,
                                   const std::string& vz);
    // Angular velocity in the owner's local frame.
    void SetFamilyPrescribedAngVel(unsigned int family, const std::string& wx, const std::string& wy,
                                   const std::string& wz);
    void DisableContactBetweenFamilies(unsigned int a, unsigned int b);
    void EnableContactBetweenFamilies(unsigned int a, unsigned int b);
    // Moves every owner of family `from` to family `to` (before or between DoDynamics calls).
    void ChangeFamily(unsigned int from, unsigned int to);
    // Moves each owner of family `from` whose state satisfies `condition` to family `to`, checked at
    // every contact detection for the rest of the run (docs/active-box.md). The condition is an
    // expression of the owner's centre X, Y, Z and velocity Vx, Vy, Vz (global frame) and the time
    // t, with comparisons and && || !, e.g. "Z < 0.1 && abs(X - 0.5*t) < 0.2". Conditions are tried
    // in the order given; an owner changes family at most once per check.
    void ChangeFamilyWhen(unsigned int from, unsigned int to, const std::string& condition);
    // Removes every condition given by ChangeFamilyWhen.
    void ClearFamilyChangeConditions();

    // ---- Trackers and inspectors ----
    std::shared_ptr<DEMTracker> Track(const std::shared_ptr<DEMClumpBatch>& batch);
    std::shared_ptr<DEMTracker> Track(const std::shared_ptr<DEMExternObj>& obj);
    std::shared_ptr<DEMTracker> Track(const std::shared_ptr<DEMMeshConnected>& mesh);
    std::shared_ptr<DEMInspector> CreateInspector(const std::string& kind);
    // An inspector over the box region [lo, hi]: "stress" (DEMInspector::GetStress).
    std::shared_ptr<DEMInspector> CreateInspector(const std::string& kind, const float3& lo, const float3& hi);

    // ---- Time stepping ----
    void SetInitTimeStep(double dt);
    // Changes the time step between DoDynamics calls (e.g. a coarse step for a settling phase, then
    // the fine one); contact history and the margin follow the new step.
    void UpdateStepSize(double dt);
    void SetGravitationalAcceleration(const float3& g);
    // A simulation whose fastest owner exceeds this speed stops with an error naming the owner.
    void SetErrorOutVelocity(float v);
    // Expected largest speed, used to size the contact margin (the measured speed is used too).
    void SetMaxVelocity(float v);
    void SetExpandSafetyMultiplier(float m);
    void SetExpandSafetyAdder(float a);
    // n_max: the most steps one contact set may serve (initial value when adaptive). Detection also
    // runs earlier whenever the margin is used up.
    void SetCDUpdateFreq(unsigned int n);
    void SetCDMaxUpdateFreq(unsigned int n);  // cap for the adaptive n_max (default 200)
    // Adapt n_max from the kinematics thread's latency (default on; asynchronous detection only).
    void UseAdaptiveUpdateFreq();
    void DisableAdaptiveUpdateFreq();
    unsigned int GetUpdateFreq() const;  // the current n_max
    // true: detect contacts on the dynamics thread every n_max steps (no overlap; for debugging and
    // bit-for-bit tests). false (default): the kinematics thread detects beside the dynamics.
    void SetSynchronousContactDetection(bool sync);
    // Whether detection runs on its own thread; by default the engine decides at Initialize():
    // asynchronous with 8 or more cores, synchronous below (docs/threads.md).
    bool UsesAsyncContactDetection() const;
    // Extra margin for the geometries of a family's owners: pairs within reach enter the contact set.
    void SetFamilyExtraMargin(unsigned int family, float margin);
    void SetInitBinSize(double size);
    // The block size of the GPU's force-pass kernel (1..1024). By default it follows the contact set:
    // 128 below 2^18 contacts, 256 above (docs/cuda-backend.md). No effect on the CPU.
    void SetForceCalcThreadsPerBlock(unsigned int n);
    // CPU threads for the parallel loops (default: OpenMP's default).
    void SetCPUThreads(unsigned int n);
    // "cpu", "cuda" or "auto" (default: $DEME_BACKEND, else "auto": CUDA where a usable GPU and
    // driver are present, else the CPU, said at INFO verbosity). See docs/cuda-backend.md.
    void SetBackend(const std::string& backend);
    // The backend in effect after Initialize: "cpu" or "cuda".
    std::string GetBackend() const;

    void Initialize();
    void DoDynamics(double duration);
    void DoDynamicsThenSync(double duration);
    void DoStepDynamics();
    // A function polled between the steps of DoDynamics (at most every 50 ms of wall time):
    // returning true stops the call after the current step, with the state consistent
    // (GetSimTime says how far it got); the next call goes on from there. A GUI's stop button, or
    // Ctrl-C in the Python module. An empty function removes it.
    void SetInterruptCheck(std::function<bool()> check);
    // Whether the last DoDynamics / DoStepDynamics call was stopped by the interrupt check.
    bool WasInterrupted() const;
    // At verbosity INFO and above, a call running longer than intervalSeconds of wall time prints a
    // progress line (simulated time and target, percent, sphere-steps/s, ETA) at most every
    // intervalSeconds, redrawn in place on a terminal, and a run summary at its end (on by default).
    void SetProgressReport(bool enable, double intervalSeconds = 5.0);
    // A function given the call's progress at every poll of the interrupt check's schedule (at most
    // every 50 ms) and once at the end (finished = true); for GUIs and the Python module. An
    // exception it throws stops the call after the current step and is rethrown by it. Empty: none.
    void SetProgressCallback(std::function<void(const RunProgress&)> callback);
    // What the last DoDynamics / DoStepDynamics call did and cost (the run summary's figures).
    RunSummary GetRunSummary() const;

    // ---- Checkpoint and restart (docs/checkpoint.md) ----
    // Writes everything the run needs to go on (state, contact set with its history, wildcards,
    // clock, step size, family rules, the adapted n_max) to one file, by a temporary name and a
    // rename: a crash while writing leaves the previous file intact. After Initialize.
    void WriteCheckpoint(const std::string& path) const;
    // Continues the run a checkpoint was taken of: call it after the script that built the same
    // scene has called Initialize(). On the CPU, the continued run is bit for bit the uninterrupted
    // one. A file that is not a checkpoint, truncated, corrupted (checksum), of another format
    // version or of another scene is a deme::Error saying which; the solver is then left as it was.
    void ReadCheckpoint(const std::string& path);

    // ---- Queries ----
    double GetSimTime() const;
    double GetTimeStep() const;
    size_t GetNumClumps() const;
    size_t GetNumSpheres() const;
    // Geometry pairs in physical contact (overlap > 0) after the last step.
    size_t GetNumContacts() const;
    // Contacts per sphere: each sphere-sphere contact counts for both spheres.
    double GetAvgSphContacts() const;
    float3 GetGravitationalAcceleration() const;

    // ---- Output (README "Output files", docs/paraview.md) ----
    // Each call copies what the file needs and returns; a writer thread writes it to a temporary
    // name and renames it, while the simulation goes on. The next output call (or FlushOutput, or
    // the solver's destruction) waits for it first; a failure to write is thrown as deme::Error by
    // that next call, which then writes nothing itself.
    void WriteSphereFile(const std::string& path) const;
    void WriteClumpFile(const std::string& path) const;
    void WriteContactFile(const std::string& path) const;
    // The coarse-grained stress of the grains over the box [lo, hi] split into nx x ny x nz cells
    // (include/deme/Stress.h, per cell): one row per cell with its centre, the stress tensor, its
    // contact and kinetic parts, the pressure and the grain count; CSV or VTU as the sphere files.
    void WriteStressField(const std::string& path, const float3& lo, const float3& hi, unsigned int nx,
                          unsigned int ny, unsigned int nz) const;
    // Waits until every file handed to the writer thread is written; throws the failure of one that
    // could not be.
    void FlushOutput() const;
    // Files written from now on by WriteSphereFile ("spheres"), WriteClumpFile ("clumps"),
    // WriteContactFile ("contacts"), WriteMeshFile ("meshes") or WriteStressField ("stress") are listed, with their simulated
    // time, in the ParaView collection pvdPath, rewritten after each frame. VTU files only. An
    // empty path ends the series.
    void SetOutputSeries(const std::string& kind, const std::string& pvdPath);
    // A PNG picture of the spheres and meshes (analytical boundaries are not drawn), rendered on the
    // CPU; the default view looks at everything from the side and above, coloured by speed.
    void WriteSnapshot(const std::string& path) const;
    void WriteSnapshot(const std::string& path, const SnapshotOptions& options) const;
    void ShowTimingStats() const;
    // Bytes of GPU memory the engine holds now (0 on the CPU backend), and a report of it.
    size_t GetDeviceMemUsage() const;
    void ShowMemStats() const;
    // Memory by array group (owner state, geometry, contacts and history, wildcards, detection
    // scratch, output staging, step scratch): GPU bytes held now and host bytes of this solver's
    // arrays, and per sphere (docs/memory.md). After Initialize.
    MemoryStats GetMemoryStats() const;
    void ShowMemoryStats() const;
    // How the kinematics and dynamics sides worked together: waits, contact-set updates, n_max,
    // false-positive share of the contact set.
    void ShowThreadCollaborationStats() const;
    // Starts those counters (and GetDynamicsWaitShare) afresh, e.g. after a settling phase, so that
    // they describe the run that follows.
    void ClearThreadCollaborationStats();
    // Share (0 to 1) of the step loop's wall time that the dynamics side spent waiting for a contact
    // set it could not step without (0 when detection is fully hidden behind the steps).
    double GetDynamicsWaitShare() const;
    // Contact sets the kinematics side detected while the dynamics side kept stepping, and that
    // were installed (asynchronous detection; 0 in synchronous mode).
    unsigned long long GetNumAsyncContactSetUpdates() const;

  private:
    void requireNotInitialized(const char* call) const;
    void requireInitialized(const char* call) const;
    void addClumpsDuringRun(const std::shared_ptr<DEMClumpBatch>& batch, const char* call);
    std::shared_ptr<DEMClumpBatch> addClumpBatch(std::shared_ptr<DEMClumpBatch> batch, const char* call);
    std::shared_ptr<DEMForceModel> chooseForceModel(const char* call, std::shared_ptr<DEMForceModel> model);
    void attachProgressHooks();
    void rethrowCallbackError();
    RunSummary runSummary(const RunProgress& p) const;
    std::unique_ptr<Scene> m_scene;
    std::shared_ptr<Simulation> m_sim;  // shared with trackers and inspectors as weak references
    // Declared after the simulation, so destroyed first: the solver's end waits for the writer thread.
    std::unique_ptr<OutputManager> m_output;
    std::unique_ptr<ProgressReporter> m_progress;
    std::function<void(const RunProgress&)> m_progressCallback;
    std::exception_ptr m_callbackError;
    int m_interruptHook = -1, m_progressHook = -1, m_callbackHook = -1;
};

}  // namespace deme
