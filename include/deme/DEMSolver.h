// DEMSolver: the user's entry point, with the method names of the paper's listings (§4).
// A thin facade: each method validates its input and forwards to the scene description (before
// Initialize) or to the running simulation.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ClumpTemplate.h"
#include "ExternalObject.h"
#include "Inspector.h"
#include "Materials.h"
#include "Mesh.h"
#include "Tracker.h"
#include "VariableTypes.h"

namespace deme {

class Scene;
class Simulation;

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
    void SetOutputFormat(const std::string& format);  // "CSV"
    // Extra sphere-file columns: "XYZ" (always written), "ABSV", "VEL", "ANG_VEL", "FAMILY", "OWNER",
    // "MAT", "QUAT". A single string may list several separated by spaces or '|'.
    void SetOutputContent(const std::string& content);
    void SetOutputContent(const std::vector<std::string>& content);

    // ---- Materials ----
    std::shared_ptr<DEMMaterial> LoadMaterial(const std::map<std::string, double>& props);
    // Pairwise value of a property (CoR, mu or Crr) between two materials; otherwise the average.
    void SetMaterialPropertyPair(const std::string& name, const std::shared_ptr<DEMMaterial>& a,
                                 const std::shared_ptr<DEMMaterial>& b, double value);

    // ---- Domain and analytical boundaries ----
    // Box of size x * y * z centred on the origin; every grain must stay inside it.
    void InstructBoxDomainDimension(float x, float y, float z);
    // Box spanning [x.first, x.second] x [y.first, y.second] x [z.first, z.second].
    void InstructBoxDomainDimension(const std::pair<float, float>& x, const std::pair<float, float>& y,
                                    const std::pair<float, float>& z);
    // Walls on the domain's faces: "all", "top_open" (no +z wall) or "none".
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
    void SetMeshOutputFormat(const std::string& format);  // "VTK"
    // Every mesh in its current pose, as one legacy VTK file (cell data: owner id).
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

    // ---- Trackers and inspectors ----
    std::shared_ptr<DEMTracker> Track(const std::shared_ptr<DEMClumpBatch>& batch);
    std::shared_ptr<DEMTracker> Track(const std::shared_ptr<DEMExternObj>& obj);
    std::shared_ptr<DEMTracker> Track(const std::shared_ptr<DEMMeshConnected>& mesh);
    std::shared_ptr<DEMInspector> CreateInspector(const std::string& kind);

    // ---- Time stepping ----
    void SetInitTimeStep(double dt);
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
    // GPU tuning hint; recorded for the CUDA backend, no effect on the CPU.
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

    // ---- Output ----
    void WriteSphereFile(const std::string& path) const;
    void WriteClumpFile(const std::string& path) const;
    void WriteContactFile(const std::string& path) const;
    void ShowTimingStats() const;
    // Bytes of GPU memory the engine holds now (0 on the CPU backend), and a report of it.
    size_t GetDeviceMemUsage() const;
    void ShowMemStats() const;
    // How the kinematics and dynamics sides worked together: waits, contact-set updates, n_max,
    // false-positive share of the contact set.
    void ShowThreadCollaborationStats() const;

  private:
    void requireNotInitialized(const char* call) const;
    void requireInitialized(const char* call) const;
    std::unique_ptr<Scene> m_scene;
    std::unique_ptr<Simulation> m_sim;
};

}  // namespace deme
