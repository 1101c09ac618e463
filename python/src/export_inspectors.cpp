// DEMInspector: a reduction over all clumps (from DEMSolver.CreateInspector), evaluated on demand.
#include "Exports.h"

#include <deme/Inspector.h>

#include <array>

namespace deme_py {

void export_inspectors(py::module_& m) {
    using I = deme::DEMInspector;
    py::class_<I, std::shared_ptr<I>>(m, "DEMInspector", "A reduction over all clumps, evaluated on demand")
        .def("GetValue", &I::GetValue, "The reduction's current value.")
        .def("GetKind", &I::GetKind,
             "clump_max_z, clump_min_z, clump_max_absv, clump_kinetic_energy, clump_mass, num_contacts or stress.")
        .def(
            "GetStress",
            [](const I& i) {
                const deme::StressTensor t = i.GetStress();
                auto matrix = [](const std::array<double, 9>& v) {
                    py::array_t<double> a({3, 3});
                    std::copy(v.begin(), v.end(), a.mutable_data());
                    return a;
                };
                py::dict d;
                d["total"] = matrix(t.total);
                d["contact"] = matrix(t.contact);
                d["kinetic"] = matrix(t.kinetic);
                d["pressure"] = t.Pressure();
                d["volume"] = t.volume;
                d["grains"] = t.grains;
                d["contacts"] = t.contacts;
                return d;
            },
            "A stress inspector's tensor: a dict of 3 x 3 numpy arrays 'total', 'contact' and 'kinetic' (Pa, "
            "compression positive), 'pressure', 'volume', 'grains' and 'contacts' (docs/periodic.md).");
}

}  // namespace deme_py
