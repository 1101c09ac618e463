// Contact force models: a handle to the model the solver uses, returned by
// DEMSolver::UseFrictionalHertzianModel, UseFrictionlessHertzianModel, DefineContactForceModel and
// ReadContactForceModel. A custom model is C++ code run once per contact pair, compiled when the
// solver initialises; docs/force-models.md lists the variables it can use.
#pragma once

#include <string>
#include <vector>

namespace deme {

class DEMForceModel {
  public:
    enum class Kind { FRICTIONAL_HERTZIAN, FRICTIONLESS_HERTZIAN, CUSTOM };

    // A built-in model, or a custom one from its source; `origin` names the source in compiler
    // messages ("force_model", or the file it was read from).
    explicit DEMForceModel(Kind kind, std::string source = "", std::string origin = "force_model");

    // Material properties every loaded material must have (checked at Initialize).
    void SetMustHaveMatProp(const std::vector<std::string>& names);
    // Properties the model reads per material pair, as name[bodyAMatType][bodyBMatType]: each pair's
    // value is the one given by SetMaterialPropertyPair, else the mean of the two materials' values;
    // every pair must have one.
    void SetMustPairwiseMatProp(const std::vector<std::string>& names);
    // Per-contact wildcards: float& variables of the model, kept while the pair stays in the contact
    // set; 0 (or SetFamilyContactWildcardInitValue's value) when a pair enters it.
    void SetPerContactWildcards(const std::vector<std::string>& names);
    // Per-owner wildcards: float* arrays indexed by AOwner / BOwner, set and read from the host.
    void SetPerOwnerWildcards(const std::vector<std::string>& names);
    // Per-geometry wildcards: float* arrays indexed by AGeo / BGeo, set and read from the host.
    void SetPerGeometryWildcards(const std::vector<std::string>& names);
    // Whether the model is called for pairs whose surfaces are apart (overlapDepth <= 0); true by
    // default (a model may act at a distance). false: such pairs get no call, no force, and their
    // contact wildcards are cleared to 0, as with the built-in models, and the engine tells most of
    // them apart before gathering any input -- for a contact model that ignores apart pairs, the same
    // results (bit for bit on the CPU), faster (docs/force-models.md, "Which pairs the model sees").
    void SetCalledForApartPairs(bool called);

    Kind GetKind() const { return m_kind; }
    const std::string& GetSource() const { return m_source; }
    const std::string& GetOrigin() const { return m_origin; }
    const std::vector<std::string>& GetMustHaveMatProp() const { return m_mustHave; }
    const std::vector<std::string>& GetMustPairwiseMatProp() const { return m_pairwise; }
    const std::vector<std::string>& GetPerContactWildcards() const { return m_contactWildcards; }
    const std::vector<std::string>& GetPerOwnerWildcards() const { return m_ownerWildcards; }
    const std::vector<std::string>& GetPerGeometryWildcards() const { return m_geometryWildcards; }
    // The built-in models: false.
    bool GetCalledForApartPairs() const { return m_calledForApartPairs; }

  private:
    friend class DEMSolver;
    // Names are checked here (valid identifiers, not a name the model already has); a built-in
    // model's lists and any model in use by an initialised solver are fixed.
    void checkEditable(const char* call) const;
    void setNames(const char* call, std::vector<std::string>& list, const std::vector<std::string>& names,
                  bool materialProperty);
    Kind m_kind;
    std::string m_source, m_origin;
    std::vector<std::string> m_mustHave, m_pairwise;
    std::vector<std::string> m_contactWildcards, m_ownerWildcards, m_geometryWildcards;
    bool m_calledForApartPairs;
    bool m_locked = false;  // set by DEMSolver::Initialize
};

}  // namespace deme
