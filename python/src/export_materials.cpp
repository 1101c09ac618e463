// DEMMaterial: a handle returned by DEMSolver.LoadMaterial({"E": ..., "nu": ..., ...}).
#include "Exports.h"

#include <deme/Error.h>
#include <deme/Materials.h>

namespace deme_py {

void export_materials(py::module_& m) {
    py::class_<deme::DEMMaterial, std::shared_ptr<deme::DEMMaterial>>(
        m, "DEMMaterial", "A loaded material: named properties (E, nu, CoR, mu, Crr, or a custom model's)")
        .def("GetProperties", &deme::DEMMaterial::GetProperties, "The properties as a dict.")
        .def(
            "Get",
            [](const deme::DEMMaterial& mat, const std::string& name) {
                const auto& props = mat.GetProperties();
                const auto it = props.find(name);
                if (it == props.end()) deme::throwError("DEMMaterial::Get", "the material has no property \"" + name + "\"");
                return it->second;
            },
            py::arg("name"), "One property's value; deme.Error if the material has none of that name.")
        .def("GetLoadOrder", &deme::DEMMaterial::GetLoadOrder,
             "Position in load order: the force model's bodyAMatType / bodyBMatType.")
        .def("__repr__", [](const deme::DEMMaterial& mat) {
            std::string s = "<deme.DEMMaterial " + std::to_string(mat.GetLoadOrder()) + ":";
            for (const auto& [k, v] : mat.GetProperties()) s += " " + k + "=" + py::repr(py::float_(v)).cast<std::string>();
            return s + ">";
        });
}

}  // namespace deme_py
