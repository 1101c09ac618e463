#include "backend/cuda/DeviceSimulation.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>

#include <deme/Error.h>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/CudaModule.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DeviceContactSet.h"
#include "backend/cuda/DeviceForceModel.h"
#include "backend/cuda/DeviceKinematics.h"
#include "backend/cuda/DevicePersistentContacts.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/EmbeddedKernel.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "dynamics/OwnerStep.h"
#include "runtime/DetectionSchedule.h"
#include "runtime/FamilyMotionSource.h"
#include "runtime/StateView.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* CALL = "DoDynamics";

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

template <class T>
void put(DeviceBuffer<T>& d, const std::vector<T>& h, Stream stream) {
    d.resizeDiscarding(h.size());
    if (!h.empty()) d.uploadAsync(h.data(), h.size(), stream);
}

template <class T>
void get(const DeviceBuffer<T>& d, std::vector<T>& h, size_t n, Stream stream) {
    h.resize(n);
    if (n) d.downloadAsync(h.data(), n, stream);
}

}  // namespace

struct DeviceSimulation::Impl {
    int device = 0;
    std::string name;
    Stream stream = nullptr;  // dT's stream: every step kernel and copy of the dynamics side
    // Around each step's force phase on dT's stream: its GPU time, read after the step's one host
    // synchronisation, splits the step between the force and integration phases (the timing report
    // and synchronous n_max adaptation use it) without a synchronisation of its own.
    cudaEvent_t forceStart = nullptr, forceEnd = nullptr;
    CudaModule dynamics, history, exchange;
    CudaKernel kResetReduction, kCopyDoubles, kClearLoads, kResolveMesh, kIntegrate, kLargeRot, kPlaceSpheres,
        kPlaceTris, kAnalytical, kMapHistory, kMaxTravelSince;
    // The families' prescriptions, compiled from the user's expressions (recompiled when they change).
    CudaModule familyModule;
    CudaKernel kFamilyMotion;
    std::string familySource;
    double compileSeconds = 0.0;
    bool fromCache = true;
    // DEME_CUDA_PROFILE_FROM_STEP: the step at which a profiler's capture starts (docs/gpu-tests.md).
    unsigned long long profileFromStep = ~0ull;
    // The contact force model's kernel and data, and the persistent-contact rules of each new set.
    DeviceForceModel model;
    DevicePersistentContacts persistence;
    DevicePrimitives prim;
    // The kinematics side: its own thread and stream, on this GPU or a second one.
    std::unique_ptr<DeviceKinematics> kinematics;

    // State (SimState's arrays).
    DeviceBuffer<voxelID_t> voxel;
    DeviceBuffer<subVoxelPos_t> subX, subY, subZ;
    DeviceBuffer<float4> oriQ;
    DeviceBuffer<float3> vel, angVel, contactForce, contactTorque, extraAcc, extraAngAcc, moi, relPos, relDirA, relPosA,
        v0, v1, v2, angVelG, sphereArm, midAngVel;
    DeviceBuffer<family_t> family;
    DeviceBuffer<uint8_t> ownerType, dynamic, anaType, anaInside, flags;
    DeviceBuffer<inertiaID_t> inertia;
    DeviceBuffer<float> extent, mass, radius, anaRadius;
    // Owners' travel, and its value at the snapshot of the set in use (baseline) and of the order in
    // flight (orderBaseline).
    DeviceBuffer<double> travel, baseline, orderBaseline;
    DeviceBuffer<bodyID_t> sphereOwner, anaOwner, triOwner;
    DeviceBuffer<materialID_t> sphereMat, anaMat, triMat;
    DeviceBuffer<uint32_t> triVertIds, vertTriStart, vertTris;
    DeviceBuffer<double3> ownerPos, spherePos, analPos, analDir, triVert;
    DeviceContacts contacts[2];
    int current = 0;
    uint32_t numContacts = 0;
    // Rules, materials, per-step inputs and results.
    DeviceBuffer<FamilyStepMotion> motion;
    DeviceBuffer<StepReduction> reduction;
    DeviceBuffer<unsigned long long> maxTravelBits;

    // Host-side copies of what the loop needs.
    StateView view{};
    unsigned int numMaterials = 0, W = 0;
    uint32_t numClumps = 0, numAnalyticalOwners = 0;
    double domainDiagonal = 0.0;
    DetectionSchedule schedule;
    bool scheduleConfigured = false;
    float lastMaxSpeed = 0.f;

    void select() const { useDevice(CALL, device); }
    void compileKernels(const ModelLayout& layout);
    void prepareFamilyMotion(const FamilyRules& families);
    void refreshView();
    // The kinematics side's order: the snapshot of the current state.
    void submit(const Settings& settings, unsigned long long step, TimingStats& timing);
    // A result arrived: installed if it may serve (DetectionSchedule::accept).
    void consider(const DeviceDetectionResult& r, unsigned long long step, TimingStats& timing,
                  CollaborationStats& collab);
    void install(const DeviceDetectionResult& r, TimingStats& timing, CollaborationStats& collab);
    double maxTravelSinceOrder();
    // Detection from the current state, waited for (synchronous mode, the first step, after edits).
    void detectNow(const Settings& settings, unsigned long long step, TimingStats& timing, CollaborationStats& collab);
    // Takes the result in flight, if any (before host edits and at DoDynamicsThenSync).
    void finishOrder(unsigned long long step, TimingStats& timing, CollaborationStats& collab);
    // Before each step: makes the set in use valid for it.
    void prepareStep(const Settings& settings, unsigned long long step, TimingStats& timing,
                     CollaborationStats& collab);
};

void DeviceSimulation::Impl::compileKernels(const ModelLayout& layout) {
    const DeviceInfo& info = useDevice("Initialize", device);
    name = info.name;
    CudaCompileOptions opt;
    opt.architecture = info.architecture();
    const std::string dynPath = "backend/cuda/kernels/Dynamics.cu", detPath = "backend/cuda/kernels/Detection.cu",
                      exPath = "backend/cuda/kernels/Exchange.cu";
    const CudaCompileResult d = compileCudaSource("Initialize", dynPath, embeddedKernelText(dynPath), opt);
    const CudaCompileResult k = compileCudaSource("Initialize", detPath, embeddedKernelText(detPath), opt);
    const CudaCompileResult x = compileCudaSource("Initialize", exPath, embeddedKernelText(exPath), opt);
    compileSeconds = d.compileSeconds + k.compileSeconds + x.compileSeconds;
    fromCache = d.cacheHit && k.cacheHit && x.cacheHit;
    dynamics = CudaModule("Initialize", d.image);
    // dT needs only the history mapping of Detection.cu; kT loads its own copy on its GPU.
    history = CudaModule("Initialize", k.image);
    exchange = CudaModule("Initialize", x.image);
    kResetReduction = dynamics.kernel("deme_reset_reduction");
    kCopyDoubles = dynamics.kernel("deme_copy_doubles");
    kClearLoads = dynamics.kernel("deme_clear_owner_loads");
    kResolveMesh = dynamics.kernel("deme_resolve_mesh_contacts");
    kIntegrate = dynamics.kernel("deme_integrate");
    kLargeRot = dynamics.kernel("deme_large_rotations");
    kPlaceSpheres = dynamics.kernel("deme_place_spheres");
    kPlaceTris = dynamics.kernel("deme_place_triangles");
    kAnalytical = dynamics.kernel("deme_analytical_step");
    kMapHistory = history.kernel("deme_map_history");
    kMaxTravelSince = exchange.kernel("deme_max_travel_since");
    model.load("Initialize (contact force model)", layout, dynamics, opt);
    persistence.load("Initialize", opt);
    compileSeconds += model.compileSeconds() + persistence.compileSeconds();
    fromCache = fromCache && model.fromCache() && persistence.fromCache();
    // Non-blocking: the legacy default stream would serialise with kT's stream on a shared GPU.
    cudaStream_t st = nullptr;
    DEME_CUDA_CHECK("Initialize", cudaStreamCreateWithFlags(&st, cudaStreamNonBlocking));
    stream = st;
    DEME_CUDA_CHECK("Initialize", cudaEventCreate(&forceStart));
    DEME_CUDA_CHECK("Initialize", cudaEventCreate(&forceEnd));
}

void DeviceSimulation::Impl::prepareFamilyMotion(const FamilyRules& families) {
    std::string source = familyMotionKernelSource(families);
    if (source == familySource) return;
    CudaCompileOptions opt;
    opt.architecture = useDevice(CALL, device).architecture();
    const CudaCompileResult r = compileCudaSource(CALL, "deme_family_motion.cu", source, opt);
    compileSeconds += r.compileSeconds;
    fromCache = fromCache && r.cacheHit;
    familyModule = CudaModule(CALL, r.image);
    kFamilyMotion = familyModule.kernel(kFamilyMotionKernel);
    familySource = std::move(source);
}

void DeviceSimulation::Impl::refreshView() {
    StateView& v = view;
    v.owners = OwnerView{voxel.data(), subX.data(),       subY.data(),          subZ.data(),     oriQ.data(),
                         vel.data(),   angVel.data(),     family.data(),        ownerType.data(), dynamic.data(),
                         inertia.data(), extent.data(),   contactForce.data(),  contactTorque.data(),
                         extraAcc.data(), extraAngAcc.data(), travel.data()};
    v.massProps = MassView{mass.data(), moi.data()};
    v.spheres = SphereView{sphereOwner.data(), relPos.data(), radius.data(), sphereMat.data()};
    v.analytical = AnalyticalView{anaOwner.data(), anaType.data(),   relPosA.data(), relDirA.data(),
                                  anaRadius.data(), anaInside.data(), anaMat.data()};
    v.triangles = TriangleView{triOwner.data(), v0.data(), v1.data(), v2.data(), triMat.data(), triVertIds.data(),
                               vertTriStart.data(), vertTris.data()};
    DeviceContacts& c = contacts[current];
    v.contacts = ContactView{c.geomA.data(), c.geomB.data(), c.type.data(),   c.wildcards.data(),
                             c.meshState.data(), c.force.data(), c.persistent.data()};
    v.cache = CacheView{ownerPos.data(), angVelG.data(), spherePos.data(), sphereArm.data(),
                        analPos.data(),  analDir.data(), triVert.data()};
    v.integrationScratch = IntegrationScratchView{flags.data(), midAngVel.data()};
    v.numContacts = numContacts;
}

void DeviceSimulation::Impl::submit(const Settings& settings, unsigned long long step, TimingStats& timing) {
    const double t0 = now();
    // The owners' travel now: the set this order yields serves while nobody travels its margin
    // beyond it.
    launch(kCopyDoubles, blocksFor(view.numOwners, THREADS), THREADS, 0, stream, orderBaseline.data(),
           (const double*)travel.data(), view.numOwners);
    const KinematicsSource src{&spherePos, &triVert, &analPos, &analDir, &family};
    kinematics->submit(src, stream, step, schedule.generation(), schedule.marginFor(settings, lastMaxSpeed));
    timing.seconds[(int)Phase::EXCHANGE] += now() - t0;
}

double DeviceSimulation::Impl::maxTravelSinceOrder() {
    maxTravelBits.zeroAsync(stream);
    launch(kMaxTravelSince, blocksFor(view.numOwners, THREADS), THREADS, 0, stream, (const double*)travel.data(),
           (const double*)orderBaseline.data(), view.numOwners, maxTravelBits.data());
    unsigned long long bits = 0;
    maxTravelBits.downloadAsync(&bits, 1, stream);
    synchronize(stream);
    double t;
    std::memcpy(&t, &bits, sizeof(double));
    return t;
}

// History mapping from the set in use (with its up-to-date wildcards) into the fresh one, then the
// fresh one serves.
void DeviceSimulation::Impl::install(const DeviceDetectionResult& r, TimingStats& timing, CollaborationStats& collab) {
    const double t0 = now();
    DeviceContacts& old = contacts[current];
    DeviceContacts& fresh = contacts[1 - current];
    // The outbox's buffers become the fresh set's pairs; the fresh set's former ones (unused since
    // the set before) become the outbox, which kT resizes before it writes.
    KinematicsOutbox& out = kinematics->outbox();
    std::swap(fresh.geomA, out.geomA);
    std::swap(fresh.geomB, out.geomB);
    std::swap(fresh.type, out.type);
    // Persistent pairs the detection missed stay in the set (DevicePersistentContacts.h).
    const ContactKeys oldKeys{old.geomA.data(), old.geomB.data(), numContacts};
    const unsigned int total = persistence.merge(fresh.geomA, fresh.geomB, fresh.type, r.numPairs, oldKeys,
                                                 old.type.data(), old.persistent.data(), prim, stream);
    fresh.resizeState(total, W);
    mapContactHistory(kMapHistory, old, numContacts, fresh, total, W, stream);
    persistence.carryOver(view, ContactKeys{fresh.geomA.data(), fresh.geomB.data(), total}, fresh.type.data(),
                          fresh.persistent.data(), fresh.wildcards.data(), W, oldKeys, old.persistent.data(), stream);
    current = 1 - current;
    numContacts = total;
    refreshView();
    // The set's snapshot is the order's: travel is measured from there.
    std::swap(baseline, orderBaseline);
    synchronize(stream);
    timing.seconds[(int)Phase::HISTORY_MAPPING] += now() - t0;
    timing.seconds[(int)Phase::BINNING] += r.binningSeconds;
    timing.seconds[(int)Phase::PAIR_SEARCH] += r.searchSeconds;
    schedule.installed(r.orderStep, r.margin, collab);
}

void DeviceSimulation::Impl::consider(const DeviceDetectionResult& r, unsigned long long step, TimingStats& timing,
                                      CollaborationStats& collab) {
    if (!schedule.accept(r.orderStep, r.generation, r.margin, step, collab, [&] { return maxTravelSinceOrder(); }))
        return;
    install(r, timing, collab);
    schedule.afterAsyncResult(collab, timing.seconds[(int)Phase::FORCE], r.binningSeconds + r.searchSeconds);
}

void DeviceSimulation::Impl::finishOrder(unsigned long long step, TimingStats& timing, CollaborationStats& collab) {
    if (!schedule.orderInFlight()) return;
    DeviceDetectionResult r;
    kinematics->waitAndTake(r);
    consider(r, step, timing, collab);
}

void DeviceSimulation::Impl::detectNow(const Settings& settings, unsigned long long step, TimingStats& timing,
                                       CollaborationStats& collab) {
    finishOrder(step, timing, collab);  // kT takes one order at a time
    const double t0 = now();
    schedule.beforeSyncDetection(settings.asyncDetection, step, collab, timing.seconds[(int)Phase::FORCE]);
    submit(settings, step, timing);
    DeviceDetectionResult r;
    kinematics->waitAndTake(r);
    // From the current state: valid by construction.
    install(r, timing, collab);
    schedule.afterSyncDetection(collab, timing.seconds[(int)Phase::FORCE], now() - t0);
}

// The CPU's schedule (ContactSetManager::prepareStep) with kT on its own stream: take a finished
// result; if the set in use may serve no longer, wait for the one in flight (or detect now); order
// the next set when kT is idle and the set in use is old enough.
void DeviceSimulation::Impl::prepareStep(const Settings& settings, unsigned long long step, TimingStats& timing,
                                         CollaborationStats& collab) {
    if (!settings.asyncDetection) {
        finishOrder(step, timing, collab);  // left from an asynchronous call before a switch
        if (schedule.due(step)) detectNow(settings, step, timing, collab);
        return;
    }
    if (schedule.needsDetection()) detectNow(settings, step, timing, collab);
    if (schedule.orderInFlight()) {
        DeviceDetectionResult r;
        if (kinematics->tryTake(r)) consider(r, step, timing, collab);
    }
    if (schedule.due(step)) {
        const double t0 = now();
        collab.dynamicsWaits++;
        finishOrder(step, timing, collab);
        if (schedule.due(step)) detectNow(settings, step, timing, collab);
        collab.dynamicsWaitSeconds += now() - t0;
    }
    if (schedule.shouldOrder(step)) {
        submit(settings, step, timing);
        schedule.ordered(collab);
    }
}

DeviceSimulation::DeviceSimulation(int device, int kinematicsDevice, const Settings& settings,
                                   const ModelLayout& model)
    : m(new Impl()) {
    (void)settings;
    m->device = device;
    m->compileKernels(model);
    if (const char* p = std::getenv("DEME_CUDA_PROFILE_FROM_STEP")) m->profileFromStep = std::strtoull(p, nullptr, 10);
    // kT starts with dT's GPU current: the exchange buffers and the event go there.
    m->kinematics.reset(new DeviceKinematics(kinematicsDevice, device));
    m->compileSeconds += m->kinematics->compileSeconds();
    m->fromCache = m->fromCache && m->kinematics->kernelsFromCache();
}

DeviceSimulation::~DeviceSimulation() {
    // kT first: its thread may still be writing into the exchange buffers.
    m->kinematics.reset();
    if (m->stream && cudaStreamDestroy(static_cast<cudaStream_t>(m->stream)) != cudaSuccess) cudaGetLastError();
    for (cudaEvent_t e : {m->forceStart, m->forceEnd})
        if (e && cudaEventDestroy(e) != cudaSuccess) cudaGetLastError();
}

void DeviceSimulation::upload(const SimState& s, const BinGrid& g, const Settings& settings,
                              const FamilyRules& families, CollaborationStats& collab) {
    Impl& d = *m;
    d.select();
    // The order in flight was detected from the state being replaced: let it finish unseen, so kT
    // is idle while its geometry changes.
    if (d.schedule.orderInFlight()) {
        DeviceDetectionResult r;
        d.kinematics->waitAndTake(r);
        d.schedule.dropped();
        collab.discardedResults++;
    }
    const Stream st = d.stream;
    const OwnerArrays& ow = s.owners;
    put(d.voxel, ow.voxel, st);
    put(d.subX, ow.subX, st);
    put(d.subY, ow.subY, st);
    put(d.subZ, ow.subZ, st);
    put(d.oriQ, ow.oriQ, st);
    put(d.vel, ow.vel, st);
    put(d.angVel, ow.angVel, st);
    put(d.family, ow.family, st);
    put(d.ownerType, ow.type, st);
    put(d.dynamic, ow.dynamic, st);
    put(d.inertia, ow.inertia, st);
    put(d.extent, ow.extent, st);
    put(d.contactForce, ow.contactForce, st);
    put(d.contactTorque, ow.contactTorque, st);
    put(d.extraAcc, ow.extraAcc, st);
    put(d.extraAngAcc, ow.extraAngAcc, st);
    put(d.travel, ow.travel, st);
    put(d.baseline, ow.travel, st);
    put(d.mass, s.massProps.mass, st);
    put(d.moi, s.massProps.moi, st);
    put(d.sphereOwner, s.spheres.owner, st);
    put(d.relPos, s.spheres.relPos, st);
    put(d.radius, s.spheres.radius, st);
    put(d.sphereMat, s.spheres.material, st);
    put(d.anaOwner, s.analytical.owner, st);
    put(d.anaType, s.analytical.type, st);
    put(d.relPosA, s.analytical.relPos, st);
    put(d.relDirA, s.analytical.relDir, st);
    put(d.anaRadius, s.analytical.radius, st);
    put(d.anaInside, s.analytical.inside, st);
    put(d.anaMat, s.analytical.material, st);
    put(d.triOwner, s.triangles.owner, st);
    put(d.v0, s.triangles.v0, st);
    put(d.v1, s.triangles.v1, st);
    put(d.v2, s.triangles.v2, st);
    put(d.triMat, s.triangles.material, st);
    put(d.triVertIds, s.triangles.vert, st);
    put(d.vertTriStart, s.triangles.vertTriStart, st);
    put(d.vertTris, s.triangles.vertTris, st);
    put(d.ownerPos, s.cache.ownerPos, st);
    put(d.angVelG, s.cache.ownerAngVelGlobal, st);
    put(d.spherePos, s.cache.spherePos, st);
    put(d.sphereArm, s.cache.sphereArm, st);
    put(d.analPos, s.cache.analPos, st);
    put(d.analDir, s.cache.analDir, st);
    put(d.triVert, s.cache.triVert, st);
    // Scratch whose contents the steps overwrite: no copy of the old contents when it grows (a copy
    // would go on the legacy default stream, unordered with dT's).
    d.flags.resizeDiscarding(ow.size());
    d.midAngVel.resizeDiscarding(ow.size());
    d.orderBaseline.resizeDiscarding(ow.size());
    // The contact set the host has (history included).
    d.W = s.numWildcards;
    d.current = 0;
    d.numContacts = (uint32_t)s.contacts.size();
    DeviceContacts& c = d.contacts[0];
    put(c.geomA, s.contacts.geomA, st);
    put(c.geomB, s.contacts.geomB, st);
    put(c.type, s.contacts.type, st);
    put(c.meshState, s.contacts.meshState, st);
    put(c.wildcards, s.contacts.wildcards, st);
    put(c.persistent, s.contacts.persistent, st);
    if (c.persistent.size() != d.numContacts) {  // not kept by the host yet: none is persistent
        c.persistent.resizeDiscarding(d.numContacts);
        c.persistent.zeroAsync(st);
    }
    c.force.resizeDiscarding(d.numContacts);
    d.numMaterials = s.materials.count;
    d.motion.resizeDiscarding(NUM_FAMILIES);
    d.reduction.resizeDiscarding(1);
    d.maxTravelBits.resizeDiscarding(1);
    synchronize(st);
    // The model's tables and wildcards and the persistence rules (copied on the legacy stream and
    // waited for, so dT's stream finds them in place).
    d.model.upload(s);
    d.persistence.uploadRules(s.wildcards.contactInit);
    synchronize(nullptr);
    // What detection reads and never changes during a run, including the family rules.
    d.kinematics->setGeometry(s, g, families, settings);

    d.view.frame = s.frame;
    d.view.domainSize = s.domainSize;
    d.view.numWildcards = s.numWildcards;
    d.view.numOwners = (uint32_t)ow.size();
    d.view.numSpheres = (uint32_t)s.spheres.size();
    d.view.numAnalytical = (uint32_t)s.analytical.size();
    d.view.numTriangles = (uint32_t)s.triangles.size();
    d.numClumps = (uint32_t)s.numClumps;
    d.numAnalyticalOwners = (uint32_t)s.numAnalyticalOwners;
    d.domainDiagonal = length(s.domainSize);
    d.refreshView();
    // n_max is configured once; later uploads (after host-side edits) keep what it adapted to.
    // kT's kernels on dT's GPU take from dT's: n_max then weighs their cost too (UpdateFrequency).
    if (!d.scheduleConfigured) d.schedule.configure(settings, d.kinematics->device() == d.device);
    d.scheduleConfigured = true;
    d.schedule.invalidate();
}

void DeviceSimulation::uploadTrackerLoads(const SimState& s) {
    m->select();
    m->extraAcc.uploadAsync(s.owners.extraAcc.data(), s.owners.extraAcc.size(), m->stream);
    m->extraAngAcc.uploadAsync(s.owners.extraAngAcc.data(), s.owners.extraAngAcc.size(), m->stream);
    // The host vectors may change before the next step reads them.
    synchronize(m->stream);
}

void DeviceSimulation::finishDetection(unsigned long long step, TimingStats& timing, CollaborationStats& collab) {
    m->select();
    m->finishOrder(step, timing, collab);
}

DeviceFault DeviceSimulation::advance(unsigned long long n, const Settings& settings, FamilyRules& families,
                                      double& time, unsigned long long& step, TimingStats& timing,
                                      CollaborationStats& collab, DeviceStepTotals& totals, RunMonitor& monitor) {
    Impl& d = *m;
    d.select();
    DeviceFault fault;
    const Stream st = d.stream;
    const unsigned int nO = d.view.numOwners, nS = d.view.numSpheres, nT = d.view.numTriangles;
    d.prepareFamilyMotion(families);
    const StepConstants consts{settings.gravity, (float)settings.dt, settings.dt,
                               settings.errorOutVelocity * settings.errorOutVelocity, d.view.frame,
                               d.view.domainSize};
    for (unsigned long long k = 0; k < n; k++) {
        // A contact set serves at most n_max steps, and only while nobody has travelled its margin.
        d.prepareStep(settings, step, timing, collab);
        if (step == d.profileFromStep) startProfilerCapture();
        const double t0 = now();
        DEME_CUDA_CHECK(CALL, cudaEventRecord(d.forceStart, static_cast<cudaStream_t>(st)));
        launch(d.kFamilyMotion, 1, NUM_FAMILIES, 0, st, time + settings.dt, d.motion.data());
        StepReduction* red = d.reduction.data();
        launch(d.kResetReduction, 1, 32, 0, st, red);
        if (nT && d.numContacts)
            launch(d.kResolveMesh, blocksFor(d.numContacts, THREADS), THREADS, 0, st, d.view, red);
        launch(d.kClearLoads, blocksFor(nO, THREADS), THREADS, 0, st, d.view);
        // Per-contact forces are stored only in a step the host can read them after: the call's
        // last, or one after which the monitor may stop the call.
        const bool polled = monitor.pollsAfterThisStep();
        StateView stepView = d.view;
        if (k + 1 < n && !polled) stepView.contacts.force = nullptr;
        d.model.launch(stepView, (float)time, (float)settings.dt, d.numClumps, nO - d.numClumps, red, st);
        DEME_CUDA_CHECK(CALL, cudaEventRecord(d.forceEnd, static_cast<cudaStream_t>(st)));
        launch(d.kIntegrate, blocksFor(nO, THREADS), THREADS, 0, st, d.view,
               (const FamilyStepMotion*)d.motion.data(), consts, (const double*)d.baseline.data(), red);
        launch(d.kLargeRot, blocksFor(nO, THREADS), THREADS, 0, st, d.view, (float)settings.dt);
        launch(d.kPlaceSpheres, blocksFor(nS, THREADS), THREADS, 0, st, d.view);
        if (nT) launch(d.kPlaceTris, blocksFor(nT, THREADS), THREADS, 0, st, d.view);
        if (d.numAnalyticalOwners)
            launch(d.kAnalytical, blocksFor(d.numAnalyticalOwners, THREADS), THREADS, 0, st, d.view, d.numClumps,
                   d.numAnalyticalOwners, (float)settings.dt, d.domainDiagonal, (const double*)d.baseline.data(), red);
        StepReduction r;
        d.reduction.downloadAsync(&r, 1, st);
        synchronize(st);
        float forceMs = 0.f;
        DEME_CUDA_CHECK(CALL, cudaEventElapsedTime(&forceMs, d.forceStart, d.forceEnd));
        const double stepSeconds = now() - t0, forceSeconds = std::min(stepSeconds, 1e-3 * (double)forceMs);
        timing.seconds[(int)Phase::FORCE] += forceSeconds;
        timing.seconds[(int)Phase::INTEGRATION] += stepSeconds - forceSeconds;

        time += settings.dt;
        step++;
        timing.steps++;
        collab.steps++;
        collab.contactSetSizeSum += (double)d.numContacts;
        collab.realContactSum += (double)r.realContacts;
        totals.realContacts = r.realContacts;
        totals.realSphereSphere = r.realSphereSphere;
        float maxSpeed;
        std::memcpy(&maxSpeed, &r.maxSpeedBits, sizeof(float));
        double maxTravel;
        std::memcpy(&maxTravel, &r.maxTravelBits, sizeof(double));
        d.lastMaxSpeed = maxSpeed;
        totals.maxSpeed = maxSpeed;
        d.schedule.afterStep(maxTravel);
        if (r.errorFlags || r.firstFault != 0xFFFFFFFFu) {
            fault.any = true;
            fault.kernelError = r.errorFlags;
            fault.kernelErrorItem = r.errorItem;
            if (r.firstFault != 0xFFFFFFFFu) {
                fault.owner = r.firstFault;
                d.flags.downloadAsync(&fault.flags, 1, st, r.firstFault);
                synchronize(st);
            }
            return fault;
        }
        if (monitor.afterStep(time)) break;
    }
    return fault;
}

void DeviceSimulation::download(SimState& s) const {
    const Impl& d = *m;
    d.select();
    OwnerArrays& ow = s.owners;
    const size_t nO = ow.size();
    get(d.voxel, ow.voxel, nO, d.stream);
    get(d.subX, ow.subX, nO, d.stream);
    get(d.subY, ow.subY, nO, d.stream);
    get(d.subZ, ow.subZ, nO, d.stream);
    get(d.oriQ, ow.oriQ, nO, d.stream);
    get(d.vel, ow.vel, nO, d.stream);
    get(d.angVel, ow.angVel, nO, d.stream);
    get(d.contactForce, ow.contactForce, nO, d.stream);
    get(d.contactTorque, ow.contactTorque, nO, d.stream);
    get(d.travel, ow.travel, nO, d.stream);
    get(d.ownerPos, s.cache.ownerPos, nO, d.stream);
    get(d.angVelG, s.cache.ownerAngVelGlobal, nO, d.stream);
    get(d.spherePos, s.cache.spherePos, s.spheres.size(), d.stream);
    get(d.sphereArm, s.cache.sphereArm, s.spheres.size(), d.stream);
    get(d.analPos, s.cache.analPos, s.analytical.size(), d.stream);
    get(d.analDir, s.cache.analDir, s.analytical.size(), d.stream);
    get(d.triVert, s.cache.triVert, 3 * s.triangles.size(), d.stream);
    const DeviceContacts& c = d.contacts[d.current];
    const size_t nc = d.numContacts;
    ContactArrays& hc = s.contacts;
    get(c.geomA, hc.geomA, nc, d.stream);
    get(c.geomB, hc.geomB, nc, d.stream);
    get(c.type, hc.type, nc, d.stream);
    get(c.meshState, hc.meshState, nc, d.stream);
    get(c.wildcards, hc.wildcards, nc * d.W, d.stream);
    get(c.force, hc.force, nc, d.stream);
    // Per-contact torques exist on the CPU only (its per-owner reduction); the GPU has none to give.
    hc.torqueA.assign(nc, make_float3(0.f));
    hc.torqueB.assign(nc, make_float3(0.f));
    get(c.persistent, hc.persistent, nc, d.stream);
    synchronize(d.stream);
    d.model.download(s);
}

unsigned int DeviceSimulation::nMax() const { return m->schedule.nMax(); }
double DeviceSimulation::margin() const { return m->schedule.margin(); }
bool DeviceSimulation::adaptiveUpdateFreq() const { return m->schedule.frequency().adaptive(); }
double DeviceSimulation::kernelCompileSeconds() const { return m->compileSeconds; }
bool DeviceSimulation::kernelsFromCache() const { return m->fromCache; }
size_t DeviceSimulation::numContacts() const { return m->numContacts; }
std::string DeviceSimulation::deviceName() const { return m->name; }
std::string DeviceSimulation::kinematicsDeviceName() const { return m->kinematics->deviceName(); }
int DeviceSimulation::kinematicsDevice() const { return m->kinematics->device(); }
bool DeviceSimulation::kinematicsPeerAccess() const { return m->kinematics->peerAccess(); }

}  // namespace deme::cuda
