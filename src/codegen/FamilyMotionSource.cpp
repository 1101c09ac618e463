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
      << "(const deme::StepBatchControl* ctl, deme::FamilyStepMotion* out, unsigned int numSteps,\n"
         "        deme::float3* contactForce, deme::float3* contactTorque, unsigned int numCleared) {\n"
         "    using namespace deme;\n"
         "    beginDependentKernel();  // first, in every thread (DependentLaunch.cuh)\n"
         "    const unsigned int i = blockIdx.x * blockDim.x + threadIdx.x;\n"
         "    if (i < numCleared) {\n"
         "        contactForce[i] = make_float3(0.f);\n"
         "        contactTorque[i] = make_float3(0.f);\n"
         "    }\n"
         "    const unsigned int k = i / NUM_FAMILIES, f = i % NUM_FAMILIES;\n"
         "    if (k >= numSteps) return;\n"
         "    // The clock at the start of step k, by the same additions as the steps make (StepBatch.h);\n"
         "    // the prescriptions at the end of the step, as the CPU evaluates them.\n"
         "    double start = ctl->time;\n"
         "    for (unsigned int j = 0; j < k; j++) start += ctl->dt;\n"
         "    const double t = start + ctl->dt;\n"
         "    FamilyStepMotion s;\n"
         "    (void)t;\n"
         "    switch (f) {\n";
    for (unsigned int f = 0; f < NUM_FAMILIES; f++)
        if (motions[f].hasAny()) writeFamily(o, f, motions[f]);
    o << "        default:\n"
         "            break;\n"
         "    }\n"
         "    out[i] = s;\n"
         "}\n";
    return o.str();
}

}  // namespace deme
