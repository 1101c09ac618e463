// The extension module deme._deme; the package deme (python/deme/__init__.py) re-exports it.
#include "Exports.h"

PYBIND11_MODULE(_deme, m) {
    m.doc() = "DEME: a Discrete Element Method engine (C++ core, method names as in C++)";
    m.attr("__version__") = DEME_VERSION;
    deme_py::export_errors(m);
    deme_py::export_types(m);
    deme_py::export_data_files(m);
    deme_py::export_materials(m);
    deme_py::export_force_models(m);
    deme_py::export_templates(m);
    deme_py::export_objects(m);
    deme_py::export_trackers(m);
    deme_py::export_inspectors(m);
    deme_py::export_samplers(m);
    deme_py::export_solver(m);
}
