// DEMForceModel: the handle of the contact model in use (built-in or a custom C++ snippet).
#include "Exports.h"

#include <deme/ForceModel.h>

namespace deme_py {

void export_force_models(py::module_& m) {
    using FM = deme::DEMForceModel;
    py::class_<FM, std::shared_ptr<FM>> cls(
        m, "DEMForceModel",
        "A contact force model; from DEMSolver.UseFrictionalHertzianModel, UseFrictionlessHertzianModel, "
        "DefineContactForceModel or ReadContactForceModel");
    py::enum_<FM::Kind>(cls, "Kind", "Built-in or custom")
        .value("FRICTIONAL_HERTZIAN", FM::Kind::FRICTIONAL_HERTZIAN)
        .value("FRICTIONLESS_HERTZIAN", FM::Kind::FRICTIONLESS_HERTZIAN)
        .value("CUSTOM", FM::Kind::CUSTOM);
    cls.def(py::init<FM::Kind, std::string, std::string>(), py::arg("kind"), py::arg("source") = "",
            py::arg("origin") = "force_model",
            "A model not yet given to a solver (DEMSolver's Use.../DefineContactForceModel make the ones it runs).")
        .def("SetMustHaveMatProp", &FM::SetMustHaveMatProp, py::arg("names"),
             "Material properties every loaded material must have (checked at Initialize).")
        .def("SetMustPairwiseMatProp", &FM::SetMustPairwiseMatProp, py::arg("names"),
             "Properties the model reads per material pair, as name[bodyAMatType][bodyBMatType].")
        .def("SetPerContactWildcards", &FM::SetPerContactWildcards, py::arg("names"),
             "Per-contact wildcards: float& variables kept while the pair stays in the contact set.")
        .def("SetPerOwnerWildcards", &FM::SetPerOwnerWildcards, py::arg("names"),
             "Per-owner wildcards: arrays indexed by AOwner / BOwner, set and read from the host.")
        .def("SetPerGeometryWildcards", &FM::SetPerGeometryWildcards, py::arg("names"),
             "Per-geometry wildcards: arrays indexed by AGeo / BGeo, set and read from the host.")
        .def("SetCalledForApartPairs", &FM::SetCalledForApartPairs, py::arg("called"),
             "Whether the model is called for pairs whose surfaces are apart (default True); False: they get "
             "no call, no force and cleared contact wildcards, as with the built-in models, and run faster.")
        .def("GetCalledForApartPairs", &FM::GetCalledForApartPairs, "See SetCalledForApartPairs.")
        .def("GetKind", &FM::GetKind, "Built-in or custom.")
        .def("GetSource", &FM::GetSource, "The snippet's C++ source (empty for a built-in model).")
        .def("GetOrigin", &FM::GetOrigin, "The name compiler messages give the source.")
        .def("GetMustHaveMatProp", &FM::GetMustHaveMatProp, "See SetMustHaveMatProp.")
        .def("GetMustPairwiseMatProp", &FM::GetMustPairwiseMatProp, "See SetMustPairwiseMatProp.")
        .def("GetPerContactWildcards", &FM::GetPerContactWildcards, "See SetPerContactWildcards.")
        .def("GetPerOwnerWildcards", &FM::GetPerOwnerWildcards, "See SetPerOwnerWildcards.")
        .def("GetPerGeometryWildcards", &FM::GetPerGeometryWildcards, "See SetPerGeometryWildcards.");
}

}  // namespace deme_py
