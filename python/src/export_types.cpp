// Constants and enums of deme/VariableTypes.h, and the functions of deme/Utils.h.
#include "Exports.h"

#include <deme/Utils.h>
#include <deme/VariableTypes.h>

namespace deme_py {

void export_types(py::module_& m) {
    m.attr("PI") = deme::PI;
    m.attr("NUM_FAMILIES") = deme::NUM_FAMILIES;
    m.attr("MAX_MATERIALS") = deme::MAX_MATERIALS;
    py::enum_<deme::AnalyticalType>(m, "AnalyticalType", "Kinds of analytical components")
        .value("ANAL_PLANE", deme::ANAL_PLANE)
        .value("ANAL_CYLINDER", deme::ANAL_CYLINDER);
    py::enum_<deme::OwnerType>(m, "OwnerType", "What an owner is")
        .value("OWNER_CLUMP", deme::OWNER_CLUMP)
        .value("OWNER_ANALYTICAL", deme::OWNER_ANALYTICAL)
        .value("OWNER_MESH", deme::OWNER_MESH);
    py::enum_<deme::ContactType>(m, "ContactType", "What a contact's B side is (A is always a sphere)")
        .value("SPHERE_SPHERE", deme::SPHERE_SPHERE)
        .value("SPHERE_ANALYTICAL", deme::SPHERE_ANALYTICAL)
        .value("SPHERE_TRIANGLE", deme::SPHERE_TRIANGLE);
    m.def("RayleighTime", &deme::RayleighTime, py::arg("r"), py::arg("density"), py::arg("E"), py::arg("nu"),
          "Rayleigh time of a sphere of radius r (explicit DEM steps are usually 5-20 % of it).");
}

}  // namespace deme_py
