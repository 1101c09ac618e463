// DEMSolver, part 3: the force model's wildcards (owner, geometry and contact) and persistent
// contacts. Ranged getters return float32 arrays; ranged setters take 1-D arrays.
#include "Exports.h"
#include "PySolver.h"

namespace deme_py {

void export_solver_wildcards(py::class_<PySolver>& c) {
    using D = deme::DEMSolver;
    c.def("SetOwnerWildcardValue", py::overload_cast<const std::string&, size_t, float>(&D::SetOwnerWildcardValue),
          py::arg("name"), py::arg("ownerID"), py::arg("value"), "One owner's wildcard value.")
        .def("SetOwnerWildcardValue",
             py::overload_cast<const std::string&, size_t, const std::vector<float>&>(&D::SetOwnerWildcardValue),
             py::arg("name"), py::arg("firstOwnerID"), py::arg("values"),
             "Owners firstOwnerID, firstOwnerID + 1, ... get values[0], values[1], ...")
        .def("SetFamilyOwnerWildcardValue", &D::SetFamilyOwnerWildcardValue, py::arg("family"), py::arg("name"),
             py::arg("value"), "Every owner of the family.")
        .def("GetOwnerWildcardValue",
             py::overload_cast<const std::string&, size_t>(&D::GetOwnerWildcardValue, py::const_), py::arg("name"),
             py::arg("ownerID"), "One owner's wildcard value.")
        .def("GetOwnerWildcardValue",
             py::overload_cast<const std::string&, size_t, size_t>(&D::GetOwnerWildcardValue, py::const_),
             py::arg("name"), py::arg("firstOwnerID"), py::arg("count"), "count owners' values from firstOwnerID, (count,).")
        .def("SetSphereWildcardValue", py::overload_cast<const std::string&, size_t, float>(&D::SetSphereWildcardValue),
             py::arg("name"), py::arg("sphereID"), py::arg("value"), "One sphere's geometry wildcard.")
        .def("SetSphereWildcardValue",
             py::overload_cast<const std::string&, size_t, const std::vector<float>&>(&D::SetSphereWildcardValue),
             py::arg("name"), py::arg("firstSphereID"), py::arg("values"), "Consecutive spheres' geometry wildcards.")
        .def("GetSphereWildcardValue",
             py::overload_cast<const std::string&, size_t>(&D::GetSphereWildcardValue, py::const_), py::arg("name"),
             py::arg("sphereID"), "One sphere's geometry wildcard.")
        .def("GetSphereWildcardValue",
             py::overload_cast<const std::string&, size_t, size_t>(&D::GetSphereWildcardValue, py::const_),
             py::arg("name"), py::arg("firstSphereID"), py::arg("count"), "count spheres' values, (count,).")
        .def("SetTriWildcardValue", &D::SetTriWildcardValue, py::arg("name"), py::arg("triangleID"), py::arg("value"),
             "A mesh triangle's geometry wildcard (index over all meshes in the order added).")
        .def("GetTriWildcardValue", &D::GetTriWildcardValue, py::arg("name"), py::arg("triangleID"),
             "A mesh triangle's geometry wildcard.")
        .def("SetAnalWildcardValue", &D::SetAnalWildcardValue, py::arg("name"), py::arg("componentID"),
             py::arg("value"), "An analytical component's geometry wildcard.")
        .def("GetAnalWildcardValue", &D::GetAnalWildcardValue, py::arg("name"), py::arg("componentID"),
             "An analytical component's geometry wildcard.")
        .def("SetContactWildcardValue", &D::SetContactWildcardValue, py::arg("name"), py::arg("value"),
             "A contact wildcard of every contact now in the set.")
        .def("SetFamilyContactWildcardValue", &D::SetFamilyContactWildcardValue, py::arg("a"), py::arg("b"),
             py::arg("name"), py::arg("value"), "A contact wildcard of the contacts between families a and b.")
        .def("SetFamilyContactWildcardValueEither", &D::SetFamilyContactWildcardValueEither, py::arg("family"),
             py::arg("name"), py::arg("value"), "... of the contacts with either owner in the family.")
        .def("SetFamilyContactWildcardValueBoth", &D::SetFamilyContactWildcardValueBoth, py::arg("family"),
             py::arg("name"), py::arg("value"), "... of the contacts with both owners in the family.")
        .def("SetFamilyContactWildcardInitValue", &D::SetFamilyContactWildcardInitValue, py::arg("a"), py::arg("b"),
             py::arg("name"), py::arg("value"), "Contacts entering the set between families a and b start at value.")
        .def("EnableOwnerWildcardOutput", &D::EnableOwnerWildcardOutput, py::arg("enable") = true,
             "Sphere and clump files get one column per owner wildcard.")
        .def("MarkPersistentContact", &D::MarkPersistentContact, "Every pair now in the set stays in it.")
        .def("MarkFamilyPersistentContact", &D::MarkFamilyPersistentContact, py::arg("a"), py::arg("b"),
             "Pairs between families a and b stay in the set.")
        .def("MarkFamilyPersistentContactEither", &D::MarkFamilyPersistentContactEither, py::arg("family"),
             "Pairs with either owner in the family stay in the set.")
        .def("MarkFamilyPersistentContactBoth", &D::MarkFamilyPersistentContactBoth, py::arg("family"),
             "Pairs with both owners in the family stay in the set.")
        .def("RemovePersistentContact", &D::RemovePersistentContact, "No pair is persistent any more.")
        .def("RemoveFamilyPersistentContact", &D::RemoveFamilyPersistentContact, py::arg("a"), py::arg("b"),
             "Pairs between families a and b are no longer persistent.")
        .def("RemoveFamilyPersistentContactEither", &D::RemoveFamilyPersistentContactEither, py::arg("family"),
             "Pairs with either owner in the family are no longer persistent.")
        .def("RemoveFamilyPersistentContactBoth", &D::RemoveFamilyPersistentContactBoth, py::arg("family"),
             "Pairs with both owners in the family are no longer persistent.")
        .def("GetNumPersistentContacts", &D::GetNumPersistentContacts, "Number of persistent pairs.");
}

}  // namespace deme_py
