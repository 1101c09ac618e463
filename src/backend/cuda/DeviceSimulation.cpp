#include "backend/cuda/DeviceSimulation.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>

#include <deme/Error.h>

#include "backend/cuda/CudaModule.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DeviceForceModel.h"
#include "backend/cuda/DevicePersistentContacts.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "backend/cuda/kernels/KernelArgs.cuh"
#include "dynamics/OwnerStep.h"
#include "jit/EmbeddedSources.h"
#include "runtime/FamilyMotionSource.h"
#include "runtime/StateView.h"

namespace deme::cuda {

namespace {

constexpr unsigned int THREADS = 256;
constexpr const char* CALL = "DoDynamics";

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

const std::string& embeddedText(const std::string& path) {
    static std::map<std::string, std::string> texts;
    auto it = texts.find(path);
    if (it != texts.end()) return it->second;
    for (const jit::EmbeddedFile& f : jit::embeddedSources())
        if (path == f.path) return texts[path] = std::string(f.text, f.size);
    throwError("Initialize", "kernel source " + path + " is not embedded in this build");
}

int bitsFor(uint64_t n) {
    int b = 1;
    while (b < 64 && (uint64_t(1) << b) <= n) b++;
    return b;
}

// One contact set on the device.
struct DeviceContacts {
    DeviceBuffer<bodyID_t> geomA, geomB;
    DeviceBuffer<uint8_t> type, meshState;
    DeviceBuffer<float> wildcards;
    DeviceBuffer<float3> force, torqueA, torqueB;
    DeviceBuffer<uint8_t> persistent;
    void resize(size_t n, unsigned int W) {
        geomA.resize(n);
        geomB.resize(n);
        type.resize(n);
        meshState.resize(n);
        wildcards.resize(n * W);
        force.resize(n);
        torqueA.resize(n);
        torqueB.resize(n);
        persistent.resize(n);
    }
};

// Items registered in bins (spheres or triangles) on the device.
struct DeviceBins {
    DeviceBuffer<int> lo, hi;
    DeviceBuffer<unsigned int> count, offset, keys, items, sortedKeys, sortedItems, start;
};

template <class T>
void put(DeviceBuffer<T>& d, const std::vector<T>& h) {
    d.resize(h.size());
    if (!h.empty()) d.uploadAsync(h.data(), h.size(), nullptr);
}

template <class T>
void get(const DeviceBuffer<T>& d, std::vector<T>& h, size_t n) {
    h.resize(n);
    if (n) d.downloadAsync(h.data(), n, nullptr);
}

}  // namespace

struct DeviceSimulation::Impl {
    int device = 0;
    std::string name;
    CudaModule dynamics, detection;
    CudaKernel kResetReduction, kCopyDoubles, kClearLoads, kResolveMesh, kIntegrate, kLargeRot, kPlaceSpheres,
        kPlaceTris, kAnalytical;
    CudaKernel kSphereBoxes, kTriBoxes, kBinEntries, kBinStarts, kPairSearch, kMapHistory;
    // The families' prescriptions, compiled from the user's expressions (recompiled when they change).
    CudaModule familyModule;
    CudaKernel kFamilyMotion;
    std::string familySource;
    double compileSeconds = 0.0;
    bool fromCache = true;
    // DEME_CUDA_PROFILE_FROM_STEP: the step at which a profiler's capture starts (docs/gpu-tests.md).
    unsigned long long profileFromStep = ~0ull;
    DevicePrimitives prim;
    DeviceForceModel model;
    DevicePersistentContacts persistence;

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
    DeviceBuffer<double> travel, baseline;
    DeviceBuffer<bodyID_t> sphereOwner, anaOwner, triOwner;
    DeviceBuffer<materialID_t> sphereMat, anaMat, triMat;
    DeviceBuffer<uint32_t> triVertIds, vertTriStart, vertTris;
    DeviceBuffer<double3> ownerPos, spherePos, analPos, analDir, triVert;
    DeviceContacts contacts[2];
    int current = 0;
    uint32_t numContacts = 0;
    // Rules, materials, per-step inputs and results.
    DeviceBuffer<FamilyStepMotion> motion;
    DeviceBuffer<uint8_t> familyMask;
    DeviceBuffer<float> familyExtraMargin;
    DeviceBuffer<StepReduction> reduction;
    // Detection scratch.
    DeviceBins sphereBins, triBins;
    DeviceBuffer<double3> triLo, triHi;
    DeviceBuffer<unsigned int> pairCount, pairOffset;

    // Host-side copies of what the loop needs.
    StateView view{};
    BinGridView grid{};
    size_t numBins = 0;
    unsigned int numMaterials = 0, W = 0;
    uint32_t numClumps = 0, numAnalyticalOwners = 0;
    double domainDiagonal = 0.0;
    UpdateFrequency freq;
    double marginNow = 0.0;
    unsigned long long acsStep = 0;
    bool needDetection = true, expired = false, freqConfigured = false;
    float lastMaxSpeed = 0.f;
    // Counters at the last detection, and what it cost (for the adaptive n_max).
    struct CostMark {
        unsigned long long steps = 0;
        double forceSeconds = 0.0, pairs = 0.0, real = 0.0, detectSeconds = 0.0;
    } costMark;

    void compileKernels(const Settings& settings, const ModelLayout& layout);
    void prepareFamilyMotion(const FamilyRules& families);
    void refreshView();
    void detect(const Settings& settings, const FamilyRules& families, TimingStats& timing);
    unsigned int readCount(const DeviceBuffer<unsigned int>& offsets, size_t at);
};

void DeviceSimulation::Impl::compileKernels(const Settings& settings, const ModelLayout& layout) {
    (void)settings;
    const DeviceInfo& info = useDevice("Initialize", device);
    name = info.name;
    CudaCompileOptions opt;
    opt.architecture = info.architecture();
    const std::string dynPath = "backend/cuda/kernels/Dynamics.cu", detPath = "backend/cuda/kernels/Detection.cu";
    const CudaCompileResult d = compileCudaSource("Initialize", dynPath, embeddedText(dynPath), opt);
    const CudaCompileResult k = compileCudaSource("Initialize", detPath, embeddedText(detPath), opt);
    compileSeconds = d.compileSeconds + k.compileSeconds;
    fromCache = d.cacheHit && k.cacheHit;
    dynamics = CudaModule("Initialize", d.image);
    detection = CudaModule("Initialize", k.image);
    kResetReduction = dynamics.kernel("deme_reset_reduction");
    kCopyDoubles = dynamics.kernel("deme_copy_doubles");
    kClearLoads = dynamics.kernel("deme_clear_owner_loads");
    kResolveMesh = dynamics.kernel("deme_resolve_mesh_contacts");
    kIntegrate = dynamics.kernel("deme_integrate");
    kLargeRot = dynamics.kernel("deme_large_rotations");
    kPlaceSpheres = dynamics.kernel("deme_place_spheres");
    kPlaceTris = dynamics.kernel("deme_place_triangles");
    kAnalytical = dynamics.kernel("deme_analytical_step");
    kSphereBoxes = detection.kernel("deme_sphere_bin_boxes");
    kTriBoxes = detection.kernel("deme_triangle_bin_boxes");
    kBinEntries = detection.kernel("deme_bin_entries");
    kBinStarts = detection.kernel("deme_bin_starts");
    kPairSearch = detection.kernel("deme_pair_search");
    kMapHistory = detection.kernel("deme_map_history");
    model.load("Initialize (contact force model)", layout, dynamics, opt);
    persistence.load("Initialize", opt);
    compileSeconds += model.compileSeconds() + persistence.compileSeconds();
    fromCache = fromCache && model.fromCache() && persistence.fromCache();
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
                             c.meshState.data(), c.force.data(), c.torqueA.data(), c.torqueB.data(),
                             c.persistent.data()};
    v.cache = CacheView{ownerPos.data(), angVelG.data(), spherePos.data(), sphereArm.data(),
                        analPos.data(),  analDir.data(), triVert.data()};
    v.integrationScratch = IntegrationScratchView{flags.data(), midAngVel.data()};
    v.numContacts = numContacts;
}

unsigned int DeviceSimulation::Impl::readCount(const DeviceBuffer<unsigned int>& offsets, size_t at) {
    unsigned int n = 0;
    offsets.downloadAsync(&n, 1, nullptr, at);
    synchronize(nullptr);
    return n;
}

// Contact detection with the current margin, then the new set takes over the old one's history.
void DeviceSimulation::Impl::detect(const Settings& settings, const FamilyRules& families, TimingStats& timing) {
    const double t0 = now();
    const unsigned int nS = view.numSpheres, nT = view.numTriangles;
    // 1. Bins of every geometry enlarged by its margin.
    auto binItems = [&](DeviceBins& b, unsigned int n, auto&& boxes) {
        b.lo.resize(3 * (size_t)n);
        b.hi.resize(3 * (size_t)n);
        b.count.resize(n + 1);
        b.offset.resize(n + 1);
        b.count.zeroAsync(nullptr);
        if (n) boxes();
        prim.exclusiveSum(b.count.data(), b.offset.data(), n + 1, nullptr);
        const unsigned int entries = readCount(b.offset, n);
        b.keys.resize(entries);
        b.items.resize(entries);
        b.sortedKeys.resize(entries);
        b.sortedItems.resize(entries);
        if (entries) {
            launch(kBinEntries, blocksFor(n, THREADS), THREADS, 0, nullptr, grid, n, (const int*)b.lo.data(),
                   (const int*)b.hi.data(), (const unsigned int*)b.offset.data(), b.keys.data(), b.items.data());
            prim.sortPairs(b.keys.data(), b.sortedKeys.data(), b.items.data(), b.sortedItems.data(), entries, nullptr,
                           0, bitsFor(numBins));
        }
        b.start.resize(numBins + 1);
        launch(kBinStarts, blocksFor((uint64_t)entries + 1, THREADS), THREADS, 0, nullptr,
               (const unsigned int*)b.sortedKeys.data(), entries, (unsigned int)numBins, b.start.data());
    };
    const float* fem = familyExtraMargin.data();
    binItems(sphereBins, nS, [&] {
        launch(kSphereBoxes, blocksFor(nS, THREADS), THREADS, 0, nullptr, view, grid, marginNow, fem,
               sphereBins.lo.data(), sphereBins.hi.data(), sphereBins.count.data());
    });
    triLo.resize(nT);
    triHi.resize(nT);
    binItems(triBins, nT, [&] {
        launch(kTriBoxes, blocksFor(nT, THREADS), THREADS, 0, nullptr, view, grid, marginNow, fem, triLo.data(),
               triHi.data(), triBins.lo.data(), triBins.hi.data(), triBins.count.data());
    });
    synchronize(nullptr);
    const double t1 = now();
    timing.seconds[(int)Phase::BINNING] += t1 - t0;

    // 2. Pair search: count, offsets, fill.
    PairSearchArgs args{grid,
                        marginNow,
                        fem,
                        familyMask.data(),
                        sphereBins.lo.data(),
                        sphereBins.hi.data(),
                        sphereBins.start.data(),
                        sphereBins.sortedItems.data(),
                        triBins.start.data(),
                        triBins.sortedItems.data(),
                        triLo.data(),
                        triHi.data()};
    pairCount.resize(nS + 1);
    pairOffset.resize(nS + 1);
    pairCount.zeroAsync(nullptr);
    launch(kPairSearch, blocksFor(nS, THREADS), THREADS, 0, nullptr, view, args, pairCount.data(),
           (const unsigned int*)nullptr, (bodyID_t*)nullptr, (bodyID_t*)nullptr, (uint8_t*)nullptr);
    prim.exclusiveSum(pairCount.data(), pairOffset.data(), nS + 1, nullptr);
    unsigned int total = readCount(pairOffset, nS);
    DeviceContacts& fresh = contacts[1 - current];
    fresh.resize(total, W);
    if (total)
        launch(kPairSearch, blocksFor(nS, THREADS), THREADS, 0, nullptr, view, args, pairCount.data(),
               (const unsigned int*)pairOffset.data(), fresh.geomA.data(), fresh.geomB.data(), fresh.type.data());
    synchronize(nullptr);
    const double t2 = now();
    timing.seconds[(int)Phase::PAIR_SEARCH] += t2 - t1;

    // 3. History: pairs found again keep their wildcards.
    DeviceContacts& old = contacts[current];
    // Persistent pairs the detection missed stay in the set (DevicePersistentContacts.h).
    const ContactKeys oldKeys{old.geomA.data(), old.geomB.data(), numContacts};
    const unsigned int detected = total;
    total = persistence.merge(fresh.geomA, fresh.geomB, fresh.type, total, oldKeys, old.type.data(),
                              old.persistent.data(), prim, nullptr);
    if (total != detected) fresh.resize(total, W);
    if (total)
        launch(kMapHistory, blocksFor(total, THREADS), THREADS, 0, nullptr, (const bodyID_t*)fresh.geomA.data(),
               (const bodyID_t*)fresh.geomB.data(), total, (const bodyID_t*)old.geomA.data(),
               (const bodyID_t*)old.geomB.data(), numContacts, (const float*)old.wildcards.data(),
               (const uint8_t*)old.meshState.data(), W, fresh.wildcards.data(), fresh.meshState.data());
    persistence.carryOver(view, ContactKeys{fresh.geomA.data(), fresh.geomB.data(), total}, fresh.type.data(),
                          fresh.persistent.data(), fresh.wildcards.data(), W, oldKeys, old.persistent.data(), nullptr);
    current = 1 - current;
    numContacts = total;
    refreshView();
    launch(kCopyDoubles, blocksFor(view.numOwners, THREADS), THREADS, 0, nullptr, baseline.data(),
           (const double*)travel.data(), view.numOwners);
    synchronize(nullptr);
    timing.seconds[(int)Phase::HISTORY_MAPPING] += now() - t2;
    (void)settings;
    (void)families;
}

DeviceSimulation::DeviceSimulation(int device, const Settings& settings, const ModelLayout& model) : m(new Impl()) {
    m->device = device;
    m->compileKernels(settings, model);
    if (const char* p = std::getenv("DEME_CUDA_PROFILE_FROM_STEP")) m->profileFromStep = std::strtoull(p, nullptr, 10);
}

DeviceSimulation::~DeviceSimulation() = default;

void DeviceSimulation::upload(const SimState& s, const BinGrid& g, const Settings& settings,
                              const FamilyRules& families) {
    Impl& d = *m;
    const OwnerArrays& ow = s.owners;
    put(d.voxel, ow.voxel);
    put(d.subX, ow.subX);
    put(d.subY, ow.subY);
    put(d.subZ, ow.subZ);
    put(d.oriQ, ow.oriQ);
    put(d.vel, ow.vel);
    put(d.angVel, ow.angVel);
    put(d.family, ow.family);
    put(d.ownerType, ow.type);
    put(d.dynamic, ow.dynamic);
    put(d.inertia, ow.inertia);
    put(d.extent, ow.extent);
    put(d.contactForce, ow.contactForce);
    put(d.contactTorque, ow.contactTorque);
    put(d.extraAcc, ow.extraAcc);
    put(d.extraAngAcc, ow.extraAngAcc);
    put(d.travel, ow.travel);
    put(d.baseline, ow.travel);
    put(d.mass, s.massProps.mass);
    put(d.moi, s.massProps.moi);
    put(d.sphereOwner, s.spheres.owner);
    put(d.relPos, s.spheres.relPos);
    put(d.radius, s.spheres.radius);
    put(d.sphereMat, s.spheres.material);
    put(d.anaOwner, s.analytical.owner);
    put(d.anaType, s.analytical.type);
    put(d.relPosA, s.analytical.relPos);
    put(d.relDirA, s.analytical.relDir);
    put(d.anaRadius, s.analytical.radius);
    put(d.anaInside, s.analytical.inside);
    put(d.anaMat, s.analytical.material);
    put(d.triOwner, s.triangles.owner);
    put(d.v0, s.triangles.v0);
    put(d.v1, s.triangles.v1);
    put(d.v2, s.triangles.v2);
    put(d.triMat, s.triangles.material);
    put(d.triVertIds, s.triangles.vert);
    put(d.vertTriStart, s.triangles.vertTriStart);
    put(d.vertTris, s.triangles.vertTris);
    put(d.ownerPos, s.cache.ownerPos);
    put(d.angVelG, s.cache.ownerAngVelGlobal);
    put(d.spherePos, s.cache.spherePos);
    put(d.sphereArm, s.cache.sphereArm);
    put(d.analPos, s.cache.analPos);
    put(d.analDir, s.cache.analDir);
    put(d.triVert, s.cache.triVert);
    d.flags.resize(ow.size());
    d.midAngVel.resize(ow.size());
    // The contact set the host has (history included).
    d.W = s.numWildcards;
    d.current = 0;
    d.numContacts = (uint32_t)s.contacts.size();
    DeviceContacts& c = d.contacts[0];
    put(c.geomA, s.contacts.geomA);
    put(c.geomB, s.contacts.geomB);
    put(c.type, s.contacts.type);
    put(c.meshState, s.contacts.meshState);
    put(c.wildcards, s.contacts.wildcards);
    put(c.persistent, s.contacts.persistent);
    if (c.persistent.size() != d.numContacts) {  // not kept by the host yet: none is persistent
        c.persistent.resize(d.numContacts);
        c.persistent.zeroAsync(nullptr);
    }
    c.force.resize(d.numContacts);
    c.torqueA.resize(d.numContacts);
    c.torqueB.resize(d.numContacts);
    // Rules and materials.
    put(d.familyMask, std::vector<uint8_t>(families.contactMask(), families.contactMask() + NUM_FAMILIES * NUM_FAMILIES));
    put(d.familyExtraMargin, std::vector<float>(settings.familyExtraMargin, settings.familyExtraMargin + NUM_FAMILIES));
    d.numMaterials = s.materials.count;
    d.model.upload(s);
    d.persistence.uploadRules(s.wildcards.contactInit);
    d.motion.resize(NUM_FAMILIES);
    d.reduction.resize(1);
    synchronize(nullptr);

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
    d.grid = BinGridView{g.origin, g.size, (int)g.nx, (int)g.ny, (int)g.nz};
    d.numBins = g.numBins();
    d.refreshView();
    // n_max is configured once; later uploads (after host-side edits) keep what it adapted to.
    if (!d.freqConfigured)
        d.freq.configure(settings.updateFreq, std::max(settings.maxUpdateFreq, settings.updateFreq),
                         settings.adaptiveUpdateFreq);
    d.freqConfigured = true;
    d.needDetection = true;
}

void DeviceSimulation::uploadTrackerLoads(const SimState& s) {
    m->extraAcc.uploadAsync(s.owners.extraAcc.data(), s.owners.extraAcc.size(), nullptr);
    m->extraAngAcc.uploadAsync(s.owners.extraAngAcc.data(), s.owners.extraAngAcc.size(), nullptr);
}

DeviceFault DeviceSimulation::advance(unsigned long long n, const Settings& settings, FamilyRules& families,
                                      double& time, unsigned long long& step, TimingStats& timing,
                                      CollaborationStats& collab, DeviceStepTotals& totals) {
    Impl& d = *m;
    DeviceFault fault;
    const unsigned int nO = d.view.numOwners, nS = d.view.numSpheres, nT = d.view.numTriangles;
    d.prepareFamilyMotion(families);
    const StepConstants consts{settings.gravity, (float)settings.dt, settings.dt,
                               settings.errorOutVelocity * settings.errorOutVelocity, d.view.frame,
                               d.view.domainSize};
    for (unsigned long long k = 0; k < n; k++) {
        // A contact set serves at most n_max steps, and only while nobody has travelled its margin.
        if (d.needDetection || d.expired || step - d.acsStep >= d.freq.nMax()) {
            if (!d.needDetection && step > d.acsStep) {
                // n_max from what detection costs against the force pass's false positives (as on the CPU).
                const Impl::CostMark& c = d.costMark;
                const double steps = (double)(collab.steps - c.steps);
                const double force = (timing.seconds[(int)Phase::FORCE] - c.forceSeconds) / steps;
                const double pairs = collab.contactSetSizeSum - c.pairs;
                const double fp = pairs > 0.0 ? 1.0 - (collab.realContactSum - c.real) / pairs : 0.0;
                d.freq.observeSyncCost(c.detectSeconds, force, fp);
            }
            const double tDetect = now();
            const double vNow = std::max<double>(d.lastMaxSpeed, settings.maxVelocity);
            const double nmax = (double)d.freq.nMax();
            const double vBound = vNow + length(settings.gravity) * nmax * settings.dt;
            d.marginNow = settings.safetyMultiplier * vBound * settings.dt * nmax + settings.safetyAdder;
            d.detect(settings, families, timing);
            d.acsStep = step;
            d.expired = d.needDetection = false;
            collab.acsUpdates++;
            collab.syncDetections++;
            d.costMark = Impl::CostMark{collab.steps, timing.seconds[(int)Phase::FORCE], collab.contactSetSizeSum,
                                        collab.realContactSum, now() - tDetect};
        }
        if (step == d.profileFromStep) startProfilerCapture();
        const double t0 = now();
        launch(d.kFamilyMotion, 1, NUM_FAMILIES, 0, nullptr, time + settings.dt, d.motion.data());
        StepReduction* red = d.reduction.data();
        launch(d.kResetReduction, 1, 32, 0, nullptr, red);
        if (nT && d.numContacts)
            launch(d.kResolveMesh, blocksFor(d.numContacts, THREADS), THREADS, 0, nullptr, d.view, red);
        launch(d.kClearLoads, blocksFor(nO, THREADS), THREADS, 0, nullptr, d.view);
        d.model.launch(d.view, (float)time, (float)settings.dt, d.numClumps, nO - d.numClumps, red, nullptr);
        synchronize(nullptr);
        const double t1 = now();
        timing.seconds[(int)Phase::FORCE] += t1 - t0;
        launch(d.kIntegrate, blocksFor(nO, THREADS), THREADS, 0, nullptr, d.view,
               (const FamilyStepMotion*)d.motion.data(), consts, (const double*)d.baseline.data(), red);
        launch(d.kLargeRot, blocksFor(nO, THREADS), THREADS, 0, nullptr, d.view, (float)settings.dt);
        launch(d.kPlaceSpheres, blocksFor(nS, THREADS), THREADS, 0, nullptr, d.view);
        if (nT) launch(d.kPlaceTris, blocksFor(nT, THREADS), THREADS, 0, nullptr, d.view);
        if (d.numAnalyticalOwners)
            launch(d.kAnalytical, blocksFor(d.numAnalyticalOwners, THREADS), THREADS, 0, nullptr, d.view, d.numClumps,
                   d.numAnalyticalOwners, (float)settings.dt, d.domainDiagonal, (const double*)d.baseline.data(), red);
        StepReduction r;
        d.reduction.downloadAsync(&r, 1, nullptr);
        synchronize(nullptr);
        timing.seconds[(int)Phase::INTEGRATION] += now() - t1;

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
        if (maxTravel > d.marginNow) d.expired = true;
        if (r.errorFlags || r.firstFault != 0xFFFFFFFFu) {
            fault.any = true;
            fault.kernelError = r.errorFlags;
            fault.kernelErrorItem = r.errorItem;
            if (r.firstFault != 0xFFFFFFFFu) {
                fault.owner = r.firstFault;
                d.flags.downloadAsync(&fault.flags, 1, nullptr, r.firstFault);
                synchronize(nullptr);
            }
            return fault;
        }
    }
    return fault;
}

void DeviceSimulation::download(SimState& s) const {
    const Impl& d = *m;
    OwnerArrays& ow = s.owners;
    const size_t nO = ow.size();
    get(d.voxel, ow.voxel, nO);
    get(d.subX, ow.subX, nO);
    get(d.subY, ow.subY, nO);
    get(d.subZ, ow.subZ, nO);
    get(d.oriQ, ow.oriQ, nO);
    get(d.vel, ow.vel, nO);
    get(d.angVel, ow.angVel, nO);
    get(d.contactForce, ow.contactForce, nO);
    get(d.contactTorque, ow.contactTorque, nO);
    get(d.travel, ow.travel, nO);
    get(d.ownerPos, s.cache.ownerPos, nO);
    get(d.angVelG, s.cache.ownerAngVelGlobal, nO);
    get(d.spherePos, s.cache.spherePos, s.spheres.size());
    get(d.sphereArm, s.cache.sphereArm, s.spheres.size());
    get(d.analPos, s.cache.analPos, s.analytical.size());
    get(d.analDir, s.cache.analDir, s.analytical.size());
    get(d.triVert, s.cache.triVert, 3 * s.triangles.size());
    const DeviceContacts& c = d.contacts[d.current];
    const size_t nc = d.numContacts;
    ContactArrays& hc = s.contacts;
    get(c.geomA, hc.geomA, nc);
    get(c.geomB, hc.geomB, nc);
    get(c.type, hc.type, nc);
    get(c.meshState, hc.meshState, nc);
    get(c.wildcards, hc.wildcards, nc * d.W);
    get(c.force, hc.force, nc);
    get(c.torqueA, hc.torqueA, nc);
    get(c.torqueB, hc.torqueB, nc);
    get(c.persistent, hc.persistent, nc);
    synchronize(nullptr);
    d.model.download(s);
}

unsigned int DeviceSimulation::nMax() const { return m->freq.nMax(); }
double DeviceSimulation::margin() const { return m->marginNow; }
double DeviceSimulation::kernelCompileSeconds() const { return m->compileSeconds; }
bool DeviceSimulation::kernelsFromCache() const { return m->fromCache; }
size_t DeviceSimulation::numContacts() const { return m->numContacts; }
std::string DeviceSimulation::deviceName() const { return m->name; }

}  // namespace deme::cuda
