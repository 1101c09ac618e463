// Family changes of single owners (docs/active-box.md): DEMSolver.ChangeFamilyWhen and the
// tracker's SetFamily / SetFamilies / GetFamilies, added to the classes the other exports made.
#include "Exports.h"
#include "PySolver.h"

#include <deme/Tracker.h>

namespace deme_py {

void export_family_changes(py::module_& m, py::class_<PySolver>& solver) {
    using D = deme::DEMSolver;
    using Tr = deme::DEMTracker;
    solver
        .def("ChangeFamilyWhen", &D::ChangeFamilyWhen, py::arg("from_"), py::arg("to"), py::arg("condition"),
             "Moves each clump of family from_ whose state satisfies the condition (an expression of X, Y, Z, "
             "Vx, Vy, Vz and t with comparisons and && || !) to family to, checked at every contact detection.")
        .def("ClearFamilyChangeConditions", &D::ClearFamilyChangeConditions,
             "Removes every condition given by ChangeFamilyWhen.");
    auto tracker = py::reinterpret_borrow<py::class_<Tr, std::shared_ptr<Tr>>>(m.attr("DEMTracker"));
    tracker
        .def("SetFamily", &Tr::SetFamily, py::arg("family"), py::arg("offset") = 0,
             "Sets the family of one tracked owner; the next step re-detects contacts.")
        .def("SetFamilies", py::overload_cast<const std::vector<unsigned int>&>(&Tr::SetFamilies), py::arg("families"),
             "Sets the family of every tracked owner (n values); all checked before any is applied.")
        .def(
            "GetFamilies",
            [](const Tr& t) {
                const std::vector<unsigned int> f = t.GetFamilies();
                py::array_t<uint32_t> out((py::ssize_t)f.size());
                std::copy(f.begin(), f.end(), out.mutable_data());
                return out;
            },
            "Families of all tracked owners, (n,) uint32.");
}

}  // namespace deme_py
