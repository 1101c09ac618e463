#include <deme/ForceModel.h>

#include <algorithm>

#include <deme/Error.h>

#include "forcemodel/Identifiers.h"

namespace deme {

DEMForceModel::DEMForceModel(Kind kind, std::string source, std::string origin)
    : m_kind(kind),
      m_source(std::move(source)),
      m_origin(std::move(origin)),
      m_calledForApartPairs(kind == Kind::CUSTOM) {
    // The built-in models' inputs, fixed: what models/HertzMindlin.inl and HertzFrictionless.inl read.
    if (kind == Kind::FRICTIONAL_HERTZIAN) {
        m_mustHave = {"E", "nu", "CoR", "mu", "Crr"};
        m_pairwise = {"CoR", "mu", "Crr"};
        m_contactWildcards = {"delta_tan_x", "delta_tan_y", "delta_tan_z", "delta_time"};
    } else if (kind == Kind::FRICTIONLESS_HERTZIAN) {
        m_mustHave = {"E", "nu", "CoR"};
        m_pairwise = {"CoR"};
    }
}

// The checks every setter of a custom model's declarations makes.
void DEMForceModel::checkEditable(const char* call) const {
    if (m_kind != Kind::CUSTOM)
        throwError(call,
                   "the built-in Hertzian models are fixed (their inputs, and which pairs they see); write a "
                   "custom model (DefineContactForceModel) to choose them");
    if (m_locked) throwError(call, "must be called before Initialize()");
}

void DEMForceModel::setNames(const char* call, std::vector<std::string>& list, const std::vector<std::string>& names,
                             bool materialProperty) {
    checkEditable(call);
    for (size_t i = 0; i < names.size(); i++) {
        const std::string& n = names[i];
        if (!isCppIdentifier(n))
            throwError(call, "\"" + n + "\" is not a C++ identifier (letters, digits, _; not starting with a digit)");
        // Material properties keep their name in the scene; wildcards become variables of the model.
        if (!materialProperty) {
            const std::string why = reservedNameReason(n);
            if (!why.empty()) throwError(call, "\"" + n + "\" cannot name a wildcard: it is " + why);
        }
        if (std::find(names.begin(), names.begin() + i, n) != names.begin() + i)
            throwError(call, "\"" + n + "\" is listed twice");
    }
    list = names;
}

void DEMForceModel::SetMustHaveMatProp(const std::vector<std::string>& names) {
    setNames("DEMForceModel::SetMustHaveMatProp", m_mustHave, names, true);
}
void DEMForceModel::SetMustPairwiseMatProp(const std::vector<std::string>& names) {
    setNames("DEMForceModel::SetMustPairwiseMatProp", m_pairwise, names, true);
}
void DEMForceModel::SetPerContactWildcards(const std::vector<std::string>& names) {
    setNames("DEMForceModel::SetPerContactWildcards", m_contactWildcards, names, false);
}
void DEMForceModel::SetPerOwnerWildcards(const std::vector<std::string>& names) {
    setNames("DEMForceModel::SetPerOwnerWildcards", m_ownerWildcards, names, false);
}
void DEMForceModel::SetPerGeometryWildcards(const std::vector<std::string>& names) {
    setNames("DEMForceModel::SetPerGeometryWildcards", m_geometryWildcards, names, false);
}

void DEMForceModel::SetCalledForApartPairs(bool called) {
    checkEditable("DEMForceModel::SetCalledForApartPairs");
    m_calledForApartPairs = called;
}

}  // namespace deme
