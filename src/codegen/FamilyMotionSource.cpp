#include "codegen/FamilyMotionSource.h"

#include <sstream>

namespace deme {

namespace {

const char* const kAxis[3] = {"x", "y", "z"};

// One family's case: which components are prescribed and their expressions of t.
void writeFamily(std::ostringstream& o, unsigned int f, const FamilyMotion& m) {
    o << "        case " << f << ":\n";
    if (m.fixed) o << "            s.fixed = 1;\n";
    for (int i = 0; i < 3; i++) {
        if (m.linPrescribed[i])
            o << "            s.linMask |= " << (1u << i) << "u;\n"
              << "            s.lin." << kAxis[i] << " = (float)" << m.lin[i].toCppSource({"t"}) << ";\n";
        if (m.angPrescribed[i])
            o << "            s.angMask |= " << (1u << i) << "u;\n"
              << "            s.ang." << kAxis[i] << " = (float)" << m.ang[i].toCppSource({"t"}) << ";\n";
    }
    o << "            break;\n";
}

}  // namespace

std::string familyMotionKernelSource(const std::array<FamilyMotion, NUM_FAMILIES>& motions) {
    std::ostringstream o;
    o << "// Generated: the families' prescribed motion (codegen/FamilyMotionSource.cpp).\n"
         "#include \"backend/cuda/kernels/DependentLaunch.cuh\"\n"
         "#include \"dynamics/StepBatch.h\"\n"
         "#include \"state/FamilyStepMotion.h\"\n"
         "\n"
         "namespace deme {\n"
         "// std::min / std::max semantics, as the CPU's evaluator has them.\n"
         "__device__ inline double deme_min(double a, double b) { return b < a ? b : a; }\n"
         "__device__ inline double deme_max(double a, double b) { return a < b ? b : a; }\n"
         "}  // namespace deme\n"
         "\n"
         "extern \"C\" __global__ void "
      << kFamilyMotionKernel
      << "(deme::StepBatchControl* ctl, deme::FamilyStepMotion* out, deme::float3* contactForce,\n"
         "        deme::float3* contactTorque, const deme::bodyID_t* clearIds, unsigned int numCleared) {\n"
         "    using namespace deme;\n"
         "    beginDependentKernel();  // first, in every thread (DependentLaunch.cuh)\n"
         "    if (ctl->stop) return;\n"
         "    const unsigned int i = blockIdx.x * blockDim.x + threadIdx.x;\n"
         "    // The step's force phase starts here: its loads cleared, its start stamped.\n"
         "    if (i == 0) {\n"
         "        unsigned long long now;\n"
         "        asm volatile(\"mov.u64 %0, %%globaltimer;\" : \"=l\"(now));\n"
         "        ctl->forcePhaseStartNs = now;\n"
         "    }\n"
         "    if (i < numCleared) {\n"
         "        const unsigned int o = clearIds ? clearIds[i] : i;\n"
         "        contactForce[o] = make_float3(0.f);\n"
         "        contactTorque[o] = make_float3(0.f);\n"
         "    }\n"
         "    const unsigned int f = i;\n"
         "    if (f >= NUM_FAMILIES) return;\n"
         "    // The prescriptions at the end of the step, as the CPU evaluates them.\n"
         "    const double t = ctl->time + ctl->dt;\n"
         "    FamilyStepMotion s;\n"
         "    (void)t;\n"
         "    switch (f) {\n";
    for (unsigned int f = 0; f < NUM_FAMILIES; f++)
        if (motions[f].hasAny()) writeFamily(o, f, motions[f]);
    o << "        default:\n"
         "            break;\n"
         "    }\n"
         "    out[f] = s;\n"
         "}\n";
    return o.str();
}

}  // namespace deme
