// Lattice samplers: fill a box, cylinder or sphere with points; each call returns an (N, 3)
// float32 array, ready for DEMSolver.AddClumps.
#include "Exports.h"

#include <deme/Samplers.h>

namespace deme_py {

namespace {

template <class S>
void samplerMethods(py::class_<S>& cls) {
    cls.def("GetSpacing", &S::GetSpacing, "The lattice spacing.")
        .def("SampleBox", &S::SampleBox, py::arg("center"), py::arg("half_dims"),
             "Points in the box center +- half_dims, (N, 3).")
        .def("SampleCylinderZ", &S::SampleCylinderZ, py::arg("center"), py::arg("radius"), py::arg("half_height"),
             "Points in a cylinder along z, (N, 3).")
        .def("SampleCylinderX", &S::SampleCylinderX, py::arg("center"), py::arg("radius"), py::arg("half_height"),
             "Points in a cylinder along x, (N, 3).")
        .def("SampleCylinderY", &S::SampleCylinderY, py::arg("center"), py::arg("radius"), py::arg("half_height"),
             "Points in a cylinder along y, (N, 3).")
        .def("SampleSphere", &S::SampleSphere, py::arg("center"), py::arg("radius"), "Points in a sphere, (N, 3).");
}

}  // namespace

void export_samplers(py::module_& m) {
    py::class_<deme::HCPSampler> hcp(m, "HCPSampler",
                                     "Hexagonal close packing: interior points have 12 neighbours at the spacing");
    hcp.def(py::init<float>(), py::arg("spacing"), "A sampler with this spacing (> 0).");
    samplerMethods(hcp);
    py::class_<deme::GridSampler> grid(m, "GridSampler", "Simple cubic grid with the spacing along every axis");
    grid.def(py::init<float>(), py::arg("spacing"), "A sampler with this spacing (> 0).");
    samplerMethods(grid);
}

}  // namespace deme_py
