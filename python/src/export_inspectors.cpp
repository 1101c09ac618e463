// DEMInspector: a reduction over all clumps (from DEMSolver.CreateInspector), evaluated on demand.
#include "Exports.h"

#include <deme/Inspector.h>

namespace deme_py {

void export_inspectors(py::module_& m) {
    using I = deme::DEMInspector;
    py::class_<I, std::shared_ptr<I>>(m, "DEMInspector", "A reduction over all clumps, evaluated on demand")
        .def("GetValue", &I::GetValue, "The reduction's current value.")
        .def("GetKind", &I::GetKind, "clump_max_z, clump_min_z, clump_max_absv, clump_kinetic_energy or num_contacts.");
}

}  // namespace deme_py
