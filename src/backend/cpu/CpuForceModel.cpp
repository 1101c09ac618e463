#include "backend/cpu/CpuForceModel.h"

#include "forcemodel/CodeGen.h"
#include "jit/HostCompiler.h"

namespace deme {

CpuForceModel loadCpuForceModel(const ModelLayout& layout, const char* call) {
    CpuForceModel m;
    m.layout = layout;
    switch (layout.kind) {
        case DEMForceModel::Kind::FRICTIONAL_HERTZIAN:
            m.pass = frictionalHertzForcePass;
            return m;
        case DEMForceModel::Kind::FRICTIONLESS_HERTZIAN:
            m.pass = frictionlessHertzForcePass;
            return m;
        default:
            break;
    }
    jit::HostCompileResult r = jit::compileHostModule(call, generateForceModelSource(layout));
    m.pass = r.module.function<ForcePassResult(SimState&, double, double, ForceStore)>(kGeneratedForcePassSymbol);
    m.module = std::make_shared<jit::CompiledModule>(std::move(r.module));
    m.cacheHit = r.cacheHit;
    m.compileSeconds = r.compileSeconds;
    return m;
}

}  // namespace deme
