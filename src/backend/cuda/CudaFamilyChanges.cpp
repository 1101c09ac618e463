// The GPU's check of the family conditions (ChangeFamilyWhen): the conditions are compiled into one
// kernel by NVRTC (codegen/FamilyConditionSource.cpp; recompiled only when they change, and found in
// the kernel cache after that), run over every owner on dT's stream. Families are then newer on the
// device than on the host, so they come back with the state (state/StateFields.h: EVOLVES).
#include <cuda_runtime_api.h>

#include "backend/cuda/CudaCheck.h"
#include "backend/cuda/CudaDynamics.h"
#include "codegen/FamilyConditionSource.h"

namespace deme::cuda {

size_t CudaDynamics::applyFamilyConditions(double time, const FamilyRules& families) {
    select();
    std::string source = familyConditionKernelSource(families.conditions());
    if (source != m_conditionSource) {
        compileGenerated("deme_family_conditions.cu", source, kFamilyConditionKernel, m_conditionModule,
                         kFamilyConditions);
        m_conditionSource = std::move(source);
    }
    if (m_changedCount.size() != 1) m_changedCount.resizeDiscarding(1);
    m_changedCount.zeroAsync(m_stream);
    const unsigned int n = m_view.numOwners;
    if (n) launch(kFamilyConditions, blocksFor(n, 256), 256, 0, m_stream, m_view, n, time, m_changedCount.data());
    unsigned int changed = 0;
    m_changedCount.downloadAsync(&changed, 1, m_stream);
    synchronize(m_stream);
    if (changed) m_subsetStale = true;
    return changed;
}

}  // namespace deme::cuda
