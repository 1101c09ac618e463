// CudaDynamics' set-up: the kernels it runs, compiled (or found in the kernel cache) by NVRTC for its
// GPU, and the families' prescription kernel, recompiled whenever the prescriptions change.
#include <cstdlib>
#include <cstring>

#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/CudaDynamics.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/EmbeddedKernel.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "codegen/FamilyMotionSource.h"
#include "runtime/RebuiltArrays.h"

namespace deme::cuda {

CudaDynamics::CudaDynamics(int device, const ModelLayout& model) : m_device(device) {
    compileKernels(model);
    if (const char* p = std::getenv("DEME_CUDA_PROFILE_FROM_STEP")) m_profileFromStep = std::strtoull(p, nullptr, 10);
    m_smallSetBytes = keepRebuiltArraysUpTo("Initialize");
    m_useGraphs = stepGraphsEnabled();
    m_overlapLaunches = overlappedLaunchesEnabled() && useDevice("Initialize", m_device).major >= 9;
    m_fusedStep = fusedStepEnabled();
    m_analyticalInBlock = analyticalInBlockEnabled();
    m_inputsBeforeWait = inputsBeforeWaitEnabled();
    m_graphSteps = stepsPerGraph();
    if (const char* v = std::getenv("DEME_CUDA_VOXEL_PRETEST"); v && *v)
        m_voxelPretestForced = std::strcmp(v, "0") != 0;
    // Both contact sets' fields, their per-contact wildcards (the history) included.
    for (DeviceContacts& set : m_contacts) {
        forEachContactField(set, set, [](auto& field, auto&, FieldRole) { field.setGroup(MemoryGroup::CONTACTS); });
        set.pairA.setGroup(MemoryGroup::CONTACTS);
    }
    for (DeviceHistoryPool& p : m_pools) {
        p.ranked.setGroup(MemoryGroup::CONTACTS);
        p.rankBase.setGroup(MemoryGroup::CONTACTS);
        p.late.setGroup(MemoryGroup::CONTACTS);
        p.lateTable.setGroup(MemoryGroup::CONTACTS);
        p.pool.setGroup(MemoryGroup::CONTACTS);
        p.meshState.setGroup(MemoryGroup::CONTACTS);
    }
    m_poolPolicy = HistoryPoolPolicy::fromEnvironment();
    m_poolPolicy.modelPools = m_model.poolsHistory();
    m_ownerSphereStart.setGroup(MemoryGroup::GEOMETRY);
    m_orderBaseline.setGroup(MemoryGroup::OWNER_STATE);
}

CudaDynamics::~CudaDynamics() {
    if (m_stream && cudaStreamDestroy(static_cast<cudaStream_t>(m_stream)) != cudaSuccess) cudaGetLastError();
    if (m_controlHost && cudaFreeHost(m_controlHost) != cudaSuccess) cudaGetLastError();
}

void CudaDynamics::select() const { useDevice("DoDynamics", m_device); }

void CudaDynamics::compileKernels(const ModelLayout& layout) {
    const DeviceInfo& info = useDevice("Initialize", m_device);
    m_name = info.name;
    CudaCompileOptions opt;
    opt.architecture = info.architecture();
    const std::string dynPath = "backend/cuda/kernels/Dynamics.cu", exPath = "backend/cuda/kernels/Exchange.cu";
    const CudaCompileResult d = compileCudaSource("Initialize", dynPath, embeddedKernelText(dynPath), opt);
    const CudaCompileResult x = compileCudaSource("Initialize", exPath, embeddedKernelText(exPath), opt);
    m_compileSeconds = d.compileSeconds + x.compileSeconds;
    m_fromCache = d.cacheHit && x.cacheHit;
    m_dynamicsModule = CudaModule("Initialize", d.image);
    m_exchangeModule = CudaModule("Initialize", x.image);
    kBeginBatch = m_dynamicsModule.kernel("deme_begin_batch");
    kClearLoads = m_dynamicsModule.kernel("deme_clear_loads");
    kResolveMesh = m_dynamicsModule.kernel("deme_resolve_mesh_contacts");
    kIntegrate = m_dynamicsModule.kernel("deme_integrate");
    kPlaceAndFinish = m_dynamicsModule.kernel("deme_place_and_finish");
    kIntegrateAndPlace = m_dynamicsModule.kernel("deme_integrate_and_place");
    kAnyOwnerAtRest = m_dynamicsModule.kernel("deme_any_owner_at_rest");
    kSteppedFlags = m_dynamicsModule.kernel("deme_stepped_flags");
    kSteppedScatter = m_dynamicsModule.kernel("deme_stepped_scatter");
    kMarkContactOwners = m_dynamicsModule.kernel("deme_mark_contact_owners");
    kScatterFlagged = m_dynamicsModule.kernel("deme_scatter_flagged");
    kFlagListed = m_dynamicsModule.kernel("deme_flag_listed");
    kGatherOwnerLoads = m_dynamicsModule.kernel("deme_gather_owner_loads");
    kMaxTravelSince = m_exchangeModule.kernel("deme_max_travel_since");
    kTravelSinceOrder = m_exchangeModule.kernel("deme_travel_since_order");
    m_model.load("Initialize (contact force model)", layout, m_dynamicsModule, opt);
    m_history.load("Initialize", opt);
    m_history.setModelWritesPersistent(!layout.builtIn());  // a custom model may set the flag (as the CPU's)
    m_compileSeconds += m_model.compileSeconds() + m_history.compileSeconds();
    m_fromCache = m_fromCache && m_model.fromCache() && m_history.fromCache();
    // Non-blocking: the legacy default stream would serialise with kT's stream on a shared GPU.
    cudaStream_t st = nullptr;
    DEME_CUDA_CHECK("Initialize", cudaStreamCreateWithFlags(&st, cudaStreamNonBlocking));
    m_stream = st;
    // The batch's control block, read back after every batch: pinned, so the copy is a plain DMA.
    void* host = nullptr;
    DEME_CUDA_CHECK("Initialize", cudaMallocHost(&host, sizeof(StepBatchControl)));
    m_controlHost = static_cast<StepBatchControl*>(host);
    m_control.resizeDiscarding(1);
    m_blocksDone.resizeDiscarding(1);
    m_blocksDone.zeroAsync(nullptr);
    m_poolControl.resizeDiscarding(1);
    m_poolControl.zeroAsync(nullptr);
    synchronize(nullptr);
}

void CudaDynamics::compileGenerated(const char* program, const std::string& source, const char* kernelName,
                                    CudaModule& module, CudaKernel& kernel) {
    CudaCompileOptions opt;
    opt.architecture = useDevice("DoDynamics", m_device).architecture();
    const CudaCompileResult r = compileCudaSource("DoDynamics", program, source, opt);
    m_compileSeconds += r.compileSeconds;
    m_fromCache = m_fromCache && r.cacheHit;
    module = CudaModule("DoDynamics", r.image);
    kernel = module.kernel(kernelName);
}

void CudaDynamics::prepareFamilyMotion(const FamilyRules& families) {
    std::string source = familyMotionKernelSource(families.motions());
    if (source == m_familySource) return;
    compileGenerated("deme_family_motion.cu", source, kFamilyMotionKernel, m_familyModule, kFamilyMotion);
    m_familySource = std::move(source);
}

}  // namespace deme::cuda
