#include "forcemodel/Identifiers.h"

#include <algorithm>
#include <cctype>
#include <iterator>

namespace deme {

namespace {

// clang-format off
// The inputs and outputs of every force model (paper Table 3, plus the engine's extras and the
// derived material tables), see docs/force-models.md.
const char* const kModelVariables[] = {
    "contactPnt", "B2A", "overlapDepth", "ts", "time", "locCPA", "locCPB", "AOwnerPos", "BOwnerPos",
    "bodyAPos", "bodyBPos", "AOriQ", "BOriQ", "AOwnerMass", "BOwnerMass", "AOwnerMOI", "BOwnerMOI",
    "ARadius", "BRadius", "bodyAMatType", "bodyBMatType", "AOwnerFamily", "BOwnerFamily", "ALinVel",
    "BLinVel", "ARotVel", "BRotVel", "AOwner", "BOwner", "AGeo", "BGeo", "armA", "armB", "rotVelCPA",
    "rotVelCPB", "force", "torque_only_force", "couple_torque", "persistent", "E_eff", "G_eff", "beta_CoR"};

// Types and helper functions a model calls (VectorTypes.h, Quaternion.h, MaterialMixing.h), the
// engine types the generated code names (forcemodel/CodeGen.cpp) and the common math functions: a
// variable of the same name would hide them.
const char* const kHelpers[] = {
    "float3", "double3", "float4", "int3", "make_float3", "make_double3", "make_float4", "make_int3",
    "to_float3", "to_double3", "dot", "cross", "length", "rotateToGlobal", "rotateToLocal",
    "applyOriQToVector3", "quatMultiply", "quatNormalize", "matProxy2ContactParam", "dampingBetaFromCoR",
    "PairTable", "ContactInputs", "deme", "PI", "std", "sqrt", "sqrtf", "pow", "powf", "exp", "expf", "log",
    "logf", "fabs", "fabsf", "abs", "sin", "sinf", "cos", "cosf", "tan", "tanf", "atan2", "atan2f", "fmin",
    "fminf", "fmax", "fmaxf", "floor", "ceil", "min", "max", "size_t", "materialID_t", "family_t", "bodyID_t",
    "SimState", "MaterialTables", "ContactArrays", "WildcardArrays", "UserForceModel", "runForcePass",
    "ForcePassResult"};

const char* const kKeywords[] = {
    "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case",
    "catch", "char", "char16_t", "char32_t", "class", "compl", "const", "constexpr", "const_cast",
    "continue", "decltype", "default", "delete", "do", "double", "dynamic_cast", "else", "enum",
    "explicit", "export", "extern", "false", "float", "for", "friend", "goto", "if", "inline", "int",
    "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq", "nullptr", "operator", "or",
    "or_eq", "private", "protected", "public", "register", "reinterpret_cast", "return", "short",
    "signed", "sizeof", "static", "static_assert", "static_cast", "struct", "switch", "template", "this",
    "thread_local", "throw", "true", "try", "typedef", "typeid", "typename", "union", "unsigned", "using",
    "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq"};
// clang-format on

template <size_t N>
bool listed(const char* const (&list)[N], const std::string& name) {
    return std::find_if(std::begin(list), std::end(list), [&](const char* k) { return name == k; }) != std::end(list);
}

}  // namespace

bool isCppIdentifier(const std::string& name) {
    if (name.empty() || !(std::isalpha((unsigned char)name[0]) || name[0] == '_')) return false;
    return std::all_of(name.begin(), name.end(), [](char ch) { return std::isalnum((unsigned char)ch) || ch == '_'; });
}

std::string reservedNameReason(const std::string& name) {
    if (listed(kKeywords, name)) return "a C++ keyword";
    if (listed(kModelVariables, name)) return "a variable every force model already has (docs/force-models.md)";
    if (listed(kHelpers, name)) return "a type or helper function force models use";
    if (name.rfind("deme_", 0) == 0) return "reserved for the engine's generated code (prefix deme_)";
    if (name.find("__") != std::string::npos ||
        (name.size() > 1 && name[0] == '_' && std::isupper((unsigned char)name[1])))
        return "reserved by the C++ standard (double underscore, or underscore and capital)";
    return "";
}

}  // namespace deme
