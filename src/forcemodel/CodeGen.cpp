#include "forcemodel/CodeGen.h"

#include <algorithm>
#include <sstream>

namespace deme {

namespace {

// The model's inputs, as the functor's local variables: (type, name) of each ContactInputs member
// (physics/ContactInputs.h), read-only.
const char* const kInputs[][2] = {{"double3", "contactPnt"},
                                  {"float3", "B2A"},
                                  {"double", "overlapDepth"},
                                  {"float", "ts"},
                                  {"float", "time"},
                                  {"float3", "locCPA"},
                                  {"float3", "locCPB"},
                                  {"double3", "AOwnerPos"},
                                  {"double3", "BOwnerPos"},
                                  {"double3", "bodyAPos"},
                                  {"double3", "bodyBPos"},
                                  {"float4", "AOriQ"},
                                  {"float4", "BOriQ"},
                                  {"float", "AOwnerMass"},
                                  {"float", "BOwnerMass"},
                                  {"float3", "AOwnerMOI"},
                                  {"float3", "BOwnerMOI"},
                                  {"float", "ARadius"},
                                  {"float", "BRadius"},
                                  {"materialID_t", "bodyAMatType"},
                                  {"materialID_t", "bodyBMatType"},
                                  {"family_t", "AOwnerFamily"},
                                  {"family_t", "BOwnerFamily"},
                                  {"float3", "ALinVel"},
                                  {"float3", "BLinVel"},
                                  {"float3", "ARotVel"},
                                  {"float3", "BRotVel"},
                                  {"bodyID_t", "AOwner"},
                                  {"bodyID_t", "BOwner"},
                                  {"bodyID_t", "AGeo"},
                                  {"bodyID_t", "BGeo"},
                                  {"float3", "armA"},
                                  {"float3", "armB"},
                                  {"float3", "rotVelCPA"},
                                  {"float3", "rotVelCPB"}};

// A string literal of `text` for a #line directive.
std::string quoted(const std::string& text) {
    std::string q = "\"";
    for (char ch : text) {
        if (ch == '"' || ch == '\\') q += '\\';
        q += (ch == '\n' || ch == '\r') ? ' ' : ch;
    }
    return q + "\"";
}

size_t lineCount(const std::string& text) { return (size_t)std::count(text.begin(), text.end(), '\n'); }

}  // namespace

std::string userForceModelSource(const ModelLayout& L, const std::string& banner,
                                 const std::vector<std::string>& includes, const std::string& constructor,
                                 const std::string& generatedName, const std::string& entry) {
    std::ostringstream o;
    o << "// " << banner << "\n";
    for (const std::string& inc : includes) o << "#include \"" << inc << "\"\n";
    o << "\n"
         "namespace deme {\n"
         "namespace {\n"
         "\n"
         "struct UserForceModel {\n"
      << "    static constexpr unsigned int kNumContactWildcards = " << L.contactWildcards.size() << ";\n"
      << "    static constexpr bool kSeesApartPairs = " << (L.calledForApartPairs ? "true" : "false") << ";\n"
      << "    static constexpr bool kWritesPersistent = true;\n"
         "    static constexpr bool kWritesCouple = true;\n"
         "\n"
         "    PairTable E_eff, G_eff, beta_CoR;\n";
    for (const auto& n : L.materialProps) o << "    const float* " << n << ";\n";
    for (const auto& n : L.pairProps) o << "    PairTable " << n << ";\n";
    for (const auto& n : L.ownerWildcards) o << "    float* " << n << ";\n";
    for (const auto& n : L.geometryWildcards) o << "    float* " << n << ";\n";
    o << "\n"
      << constructor
      << "\n"
         "    DEME_HD_INLINE void operator()(const ContactInputs& deme_in, float* deme_contactWildcards, float3& "
         "force,\n"
         "                                   float3& torque_only_force, float3& couple_torque, bool& persistent) const {\n";
    for (const auto& v : kInputs) o << "        const " << v[0] << " " << v[1] << " = deme_in." << v[1] << ";\n";
    for (size_t i = 0; i < L.contactWildcards.size(); i++)
        o << "        float& " << L.contactWildcards[i] << " = deme_contactWildcards[" << i << "];\n";
    // Whatever the code leaves unused is not computed (the gather is inlined); the casts only silence
    // unused-variable warnings.
    for (const auto& v : kInputs) o << "        (void)" << v[1] << ";\n";
    o << "        (void)deme_contactWildcards;\n"
         "        (void)force;\n"
         "        (void)torque_only_force;\n"
         "        (void)couple_torque;\n"
         "        (void)persistent;\n"
         // The user's code in a block of its own, so that it may declare names the prologue has.
         "        {\n"
         "#line 1 "
      << quoted(L.origin) << "\n"
      << L.source << "\n";
    // Back to the generated text's own numbering: the directive is on line `lines + 1`.
    const size_t lines = lineCount(o.str());
    o << "#line " << lines + 2 << " " << quoted(generatedName) << "\n"
      << "        }\n"
         "    }\n"
         "};\n"
         "\n"
         "}  // namespace\n"
         "}  // namespace deme\n"
         "\n"
      << entry;
    return o.str();
}

std::string generateForceModelSource(const ModelLayout& L) {
    std::ostringstream ctor;
    ctor << "    explicit UserForceModel(SimState& deme_s) {\n"
            "        const MaterialTables& deme_m = deme_s.materials;\n"
            "        E_eff = PairTable{deme_m.E_eff.data(), deme_m.count};\n"
            "        G_eff = PairTable{deme_m.G_eff.data(), deme_m.count};\n"
            "        beta_CoR = PairTable{deme_m.beta_CoR.data(), deme_m.count};\n";
    for (size_t i = 0; i < L.materialProps.size(); i++)
        ctor << "        " << L.materialProps[i] << " = deme_m.props[" << i << "].data();\n";
    for (size_t i = 0; i < L.pairProps.size(); i++)
        ctor << "        " << L.pairProps[i] << " = PairTable{deme_m.pairProps[" << i << "].data(), deme_m.count};\n";
    for (size_t i = 0; i < L.ownerWildcards.size(); i++)
        ctor << "        " << L.ownerWildcards[i] << " = deme_s.wildcards.owner[" << i << "].data();\n";
    for (size_t i = 0; i < L.geometryWildcards.size(); i++)
        ctor << "        " << L.geometryWildcards[i] << " = deme_s.wildcards.geometry[" << i << "].data();\n";
    ctor << "    }\n";
    const std::string entry = std::string("extern \"C\" deme::ForcePassResult ") + kGeneratedForcePassSymbol +
                              "(deme::SimState& s, double time, double dt, deme::ForceStore store) {\n"
                              "    return deme::runForcePass(s, deme::UserForceModel(s), time, dt, store);\n"
                              "}\n";
    return userForceModelSource(L, "Generated by DEME from a custom contact force model (docs/force-models.md).",
                                {"backend/cpu/ForcePassLoop.h", "physics/MaterialMixing.h", "physics/Quaternion.h"},
                                ctor.str(), "deme_generated_force_model.cpp", entry);
}

}  // namespace deme
