#include "api/ForceModelSetup.h"

#include <algorithm>
#include <optional>
#include <set>

#include <deme/Error.h>

#include "forcemodel/Identifiers.h"
#include "physics/MaterialMixing.h"

namespace deme {

namespace {

// The properties the built-in models read (and LoadMaterial range-checks).
const std::vector<std::string> kStandardProps = {"E", "nu", "CoR", "mu", "Crr"};

std::optional<double> materialValue(const Scene& scene, const std::string& name, size_t m) {
    const auto& props = scene.materials[m]->GetProperties();
    const auto it = props.find(name);
    if (it == props.end()) return std::nullopt;
    return it->second;
}

// A pair's value: the one given by SetMaterialPropertyPair, else the mean of both materials' values.
std::optional<double> pairValue(const Scene& scene, const std::string& name, size_t a, size_t b) {
    const auto it = scene.pairProperties.find({name, (unsigned)std::min(a, b), (unsigned)std::max(a, b)});
    if (it != scene.pairProperties.end()) return it->second;
    const auto va = materialValue(scene, name, a), vb = materialValue(scene, name, b);
    if (va && vb) return 0.5 * (*va + *vb);
    return std::nullopt;
}

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::string propertyList(const Scene& scene, size_t m) {
    std::vector<std::string> names;
    for (const auto& kv : scene.materials[m]->GetProperties()) names.push_back(kv.first);
    return joined(names);
}

}  // namespace

ModelLayout resolveModelLayout(const DEMForceModel& model, const Scene& scene, const char* call) {
    ModelLayout L;
    L.kind = model.GetKind();
    L.source = model.GetSource();
    L.origin = model.GetOrigin();
    L.pairProps = model.GetMustPairwiseMatProp();
    L.contactWildcards = model.GetPerContactWildcards();
    L.ownerWildcards = model.GetPerOwnerWildcards();
    L.geometryWildcards = model.GetPerGeometryWildcards();
    L.calledForApartPairs = model.GetCalledForApartPairs();
    const std::string who = L.description();
    const size_t nMat = scene.materials.size();

    for (size_t m = 0; m < nMat; m++) {
        for (const std::string& name : model.GetMustHaveMatProp())
            if (!materialValue(scene, name, m))
                throwError(call, "material " + std::to_string(m) + " (in load order) has no property \"" + name +
                                     "\", which " + who + " needs (it has: " + propertyList(scene, m) + ")");
        if (L.builtIn())
            for (const auto& kv : scene.materials[m]->GetProperties())
                if (indexOf(kStandardProps, kv.first) < 0)
                    throwError(call, "material " + std::to_string(m) + " has property \"" + kv.first + "\", which " +
                                         who + " does not read (" + joined(kStandardProps) +
                                         "); a custom model (DefineContactForceModel) can read any property");
    }
    for (const std::string& name : L.pairProps)
        for (size_t a = 0; a < nMat; a++)
            for (size_t b = a; b < nMat; b++)
                if (!pairValue(scene, name, a, b))
                    throwError(call, "materials " + std::to_string(a) + " and " + std::to_string(b) +
                                         " have no value of \"" + name + "\", which " + who +
                                         " reads per material pair: give both materials the property, or call "
                                         "SetMaterialPropertyPair");
    for (const auto& kv : scene.pairProperties) {
        const std::string& name = std::get<0>(kv.first);
        if (indexOf(L.pairProps, name) < 0)
            throwError(call, "SetMaterialPropertyPair gave \"" + name + "\" for materials " +
                                 std::to_string(std::get<1>(kv.first)) + " and " +
                                 std::to_string(std::get<2>(kv.first)) + ", but " + who + " does not read \"" + name +
                                 "\" per material pair (declare it with SetMustPairwiseMatProp)");
    }
    if (L.builtIn()) return L;

    // A custom model sees every property of any material, per material unless it reads it per pair
    // (absent values read as 0), and every name becomes one of its variables: no two may clash.
    std::set<std::string> props;
    for (const auto& mat : scene.materials)
        for (const auto& kv : mat->GetProperties())
            if (indexOf(L.pairProps, kv.first) < 0) props.insert(kv.first);
    L.materialProps.assign(props.begin(), props.end());
    std::set<std::string> seen;
    auto claim = [&](const std::string& name, const char* what) {
        const std::string why = reservedNameReason(name);
        if (!why.empty())
            throwError(call,
                       std::string(what) + " \"" + name + "\" cannot be a variable of the force model: it is " + why);
        if (!seen.insert(name).second)
            throwError(call, "the name \"" + name + "\" is used twice by the force model (as " + what +
                                 " and as another material property or wildcard)");
    };
    for (const auto& n : L.materialProps) claim(n, "material property");
    for (const auto& n : L.pairProps) claim(n, "pairwise material property");
    for (const auto& n : L.contactWildcards) claim(n, "contact wildcard");
    for (const auto& n : L.ownerWildcards) claim(n, "owner wildcard");
    for (const auto& n : L.geometryWildcards) claim(n, "geometry wildcard");
    return L;
}

void buildMaterialTables(const Scene& scene, const ModelLayout& layout, MaterialTables& mt) {
    const size_t n = scene.materials.size();
    mt.count = (unsigned int)n;
    auto perMaterial = [&](const std::string& name) {
        std::vector<float> t(n, 0.f);
        for (size_t m = 0; m < n; m++) t[m] = (float)materialValue(scene, name, m).value_or(0.0);
        return t;
    };
    auto perPair = [&](const std::string& name) {
        std::vector<float> t(n * n, 0.f);
        for (size_t a = 0; a < n; a++)
            for (size_t b = 0; b < n; b++) t[a * n + b] = (float)pairValue(scene, name, a, b).value_or(0.0);
        return t;
    };
    mt.E = perMaterial("E");
    mt.nu = perMaterial("nu");
    mt.CoR = perPair("CoR");
    mt.mu = perPair("mu");
    mt.Crr = perPair("Crr");
    // Derived per pair (MaterialMixing.h), where the inputs exist; 0 otherwise.
    mt.E_eff.assign(n * n, 0.f);
    mt.G_eff.assign(n * n, 0.f);
    mt.beta_CoR.assign(n * n, 0.f);
    for (size_t a = 0; a < n; a++)
        for (size_t b = 0; b < n; b++) {
            if (mt.E[a] > 0.f && mt.E[b] > 0.f)
                matProxy2ContactParam(mt.E_eff[a * n + b], mt.G_eff[a * n + b], mt.E[a], mt.nu[a], mt.E[b], mt.nu[b]);
            if (pairValue(scene, "CoR", a, b)) mt.beta_CoR[a * n + b] = dampingBetaFromCoR(mt.CoR[a * n + b]);
        }
    mt.props.clear();
    mt.pairProps.clear();
    for (const auto& name : layout.materialProps) mt.props.push_back(perMaterial(name));
    for (const auto& name : layout.pairProps) mt.pairProps.push_back(perPair(name));
}

}  // namespace deme
