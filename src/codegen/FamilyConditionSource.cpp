#include "codegen/FamilyConditionSource.h"

#include <sstream>

namespace deme {

std::string familyConditionKernelSource(const std::vector<FamilyCondition>& conditions) {
    std::ostringstream o;
    o << "// Generated: the family conditions (codegen/FamilyConditionSource.cpp).\n"
         "#include \"dynamics/FamilyChangeRule.h\"\n"
         "#include \"state/StateView.h\"\n"
         "\n"
         "// std::min / std::max semantics, as the CPU's evaluator has them (outside namespace deme: the\n"
         "// kernel below is, so that atomicAdd's overloads do not meet deme's vector types).\n"
         "__device__ inline double deme_min(double a, double b) { return b < a ? b : a; }\n"
         "__device__ inline double deme_max(double a, double b) { return a < b ? b : a; }\n"
         "\n"
         "extern \"C\" __global__ void "
      << kFamilyConditionKernel
      << "(deme::StateView s, unsigned int numOwners, double t, unsigned int* changed) {\n"
         "    const unsigned int o = blockIdx.x * blockDim.x + threadIdx.x;\n"
         "    if (o >= numOwners) return;\n"
         "    double v[deme::FAMILY_CONDITION_VARS];\n"
         "    deme::familyConditionInputs(s, o, t, v);\n"
         "    (void)v;\n";
    const std::vector<std::string> vars{"v[0]", "v[1]", "v[2]", "v[3]", "v[4]", "v[5]", "v[6]"};
    for (const FamilyCondition& c : conditions)
        o << "    if (s.owners.family[o] == " << (unsigned)c.from << "u && deme::applyFamilyRule(s, o, (deme::family_t)"
          << (unsigned)c.from << ", (deme::family_t)" << (unsigned)c.to << ", " << c.when.toCppSource(vars)
          << ")) {\n"
             "        atomicAdd(changed, 1u);\n"
             "        return;\n"
             "    }\n";
    o << "}\n";
    return o.str();
}

}  // namespace deme
