#include "backend/cuda/DeviceForceModel.h"

#include <cstddef>
#include <cstdlib>
#include <string>

#include <deme/Error.h>

#include "backend/cuda/kernels/KernelArgs.cuh"
#include "forcemodel/CudaCodeGen.h"
#include "state/StateView.h"

namespace deme::cuda {

namespace {

// Rows of equal length, one after the other (ForceModelParams' layout); `rowLength` is checked.
std::vector<float> flatten(const std::vector<std::vector<float>>& rows, size_t rowLength, const char* what) {
    std::vector<float> flat;
    flat.reserve(rows.size() * rowLength);
    for (const std::vector<float>& r : rows) {
        if (r.size() != rowLength)
            throwError("DoDynamics", std::string("internal: a ") + what + " table has " + std::to_string(r.size()) +
                                         " values, expected " + std::to_string(rowLength));
        flat.insert(flat.end(), r.begin(), r.end());
    }
    return flat;
}

void put(DeviceBuffer<float>& d, const std::vector<float>& h) {
    d.resize(h.size());
    if (!h.empty()) d.uploadAsync(h.data(), h.size(), nullptr);
}

}  // namespace

void DeviceForceModel::load(const std::string& call, const ModelLayout& layout, const CudaModule& dynamics,
                            const CudaCompileOptions& options) {
    // The built-in passes capped at 64 registers (BENCHMARKS.md, SMALL-SYSTEMS: twice the resident
    // blocks for a few spilled values); DEME_CUDA_FORCE_REGS=0 takes the uncapped ones.
    const char* regs = std::getenv("DEME_CUDA_FORCE_REGS");
    const std::string variant = regs && std::string(regs) == "0" ? "" : "_r64";
    // A pass for scenes without meshes leaves the triangle branch out (kernels/ForcePassKernel.cuh);
    // DEME_CUDA_NO_MESH_PASS=0 keeps the pass of every type.
    const char* noMesh = std::getenv("DEME_CUDA_NO_MESH_PASS");
    const bool withNoMesh = !(noMesh && std::string(noMesh) == "0");
    std::string name;
    switch (layout.kind) {
        case DEMForceModel::Kind::FRICTIONAL_HERTZIAN:
            name = "deme_force_pass_frictional_hertz";
            break;
        case DEMForceModel::Kind::FRICTIONLESS_HERTZIAN:
            name = "deme_force_pass_frictionless_hertz";
            break;
        default:
            break;
    }
    if (!name.empty()) {
        m_kernel = dynamics.kernel(name + variant);
        if (withNoMesh) m_noMeshKernel = dynamics.kernel(name + "_no_mesh" + variant);
        // The frictional model's passes over a pooled history (state/HistoryPool.h). The frictionless
        // model keeps no history; a custom model may write more than its pair's history and loads
        // (its `persistent` flag, owner wildcards), which a pending pair's second step would repeat.
        if (layout.kind == DEMForceModel::Kind::FRICTIONAL_HERTZIAN) {
            m_pooledKernel = dynamics.kernel(name + "_pooled" + variant);
            if (withNoMesh) m_pooledNoMeshKernel = dynamics.kernel(name + "_pooled_no_mesh" + variant);
        }
        return;
    }
    const CudaCompileResult r =
        compileCudaSource(call, kGeneratedForceKernelProgram, generateCudaForceModelSource(layout), options);
    m_compileSeconds = r.compileSeconds;
    m_fromCache = r.cacheHit;
    m_module = CudaModule(call, r.image);
    m_kernel = m_module.kernel(kGeneratedForceKernelSymbol);
    if (withNoMesh) m_noMeshKernel = m_module.kernel(kGeneratedNoMeshForceKernelSymbol);
}

void DeviceForceModel::upload(const SimState& s) {
    const MaterialTables& mt = s.materials;
    const size_t nM = mt.count;
    const size_t nOwners = s.owners.size();
    const size_t nGeometries = s.spheres.size() + s.analytical.size() + s.triangles.size();
    put(m_mu, mt.mu);
    put(m_Crr, mt.Crr);
    put(m_E_eff, mt.E_eff);
    put(m_G_eff, mt.G_eff);
    put(m_beta_CoR, mt.beta_CoR);
    // Host vectors are copied by asynchronous copies: keep them alive until the copies are done.
    const std::vector<float> props = flatten(mt.props, nM, "material property");
    const std::vector<float> pairProps = flatten(mt.pairProps, nM * nM, "pair property");
    const std::vector<float> owner = flatten(s.wildcards.owner, nOwners, "owner wildcard");
    const std::vector<float> geometry = flatten(s.wildcards.geometry, nGeometries, "geometry wildcard");
    put(m_props, props);
    put(m_pairProps, pairProps);
    m_ownerWildcards.setGroup(MemoryGroup::WILDCARDS);
    m_geometryWildcards.setGroup(MemoryGroup::WILDCARDS);
    put(m_ownerWildcards, owner);
    put(m_geometryWildcards, geometry);
    synchronize(nullptr);
    m_numOwnerWildcards = s.wildcards.owner.size();
    m_numGeometryWildcards = s.wildcards.geometry.size();
    m_params = ForceModelParams{m_mu.data(),
                                m_Crr.data(),
                                m_E_eff.data(),
                                m_G_eff.data(),
                                m_beta_CoR.data(),
                                m_props.data(),
                                m_pairProps.data(),
                                m_ownerWildcards.data(),
                                m_geometryWildcards.data(),
                                (unsigned int)nM,
                                (unsigned int)nOwners,
                                (unsigned int)nGeometries};
}

void DeviceForceModel::download(SimState& s) const {
    auto fetch = [](const DeviceBuffer<float>& d, std::vector<std::vector<float>>& rows, size_t count,
                    size_t rowLength) {
        if (count == 0 || rowLength == 0) return;
        std::vector<float> flat(count * rowLength);
        d.downloadAsync(flat.data(), flat.size(), nullptr);
        synchronize(nullptr);
        rows.resize(count);
        for (size_t w = 0; w < count; w++)
            rows[w].assign(flat.begin() + (ptrdiff_t)(w * rowLength), flat.begin() + (ptrdiff_t)((w + 1) * rowLength));
    };
    fetch(m_ownerWildcards, s.wildcards.owner, m_numOwnerWildcards, m_params.numOwners);
    fetch(m_geometryWildcards, s.wildcards.geometry, m_numGeometryWildcards, m_params.numGeometries);
}

void DeviceForceModel::record(LaunchList& list, const StateView& view, const StepBatchControl* ctl,
                              unsigned int firstNonClump, unsigned int numNonClump, StepReduction* red,
                              unsigned int threadsPerBlock) const {
    if (view.numContacts == 0) return;
    const bool noMesh = view.numTriangles == 0 && m_noMeshKernel.handle;
    const CudaKernel& pass = view.historyPool.ranked ? (noMesh ? m_pooledNoMeshKernel : m_pooledKernel)
                                                     : (noMesh ? m_noMeshKernel : m_kernel);
    if (!pass.handle)
        throwError("DoDynamics", "internal: the contact set's history is pooled, but the model has no pooled pass");
    list.kernel(pass, blocksFor(view.numContacts, threadsPerBlock), threadsPerBlock, 0, view, ctl, m_params,
                firstNonClump, numNonClump, red);
}

}  // namespace deme::cuda
