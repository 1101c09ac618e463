// The output calls of DEMSolver that came with VTU/PVD output, snapshots and the progress report
// (docs/paraview.md, README "Output files"), and their small structs: SnapshotOptions, RunProgress,
// RunSummary.
#include <functional>

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "Exports.h"
#include "PySolver.h"

namespace deme_py {

namespace {

using S = PySolver;
using D = deme::DEMSolver;

void exportStructs(py::module_& m) {
    py::class_<deme::SnapshotOptions>(m, "SnapshotOptions", "Options of DEMSolver.WriteSnapshot")
        .def(py::init<>())
        .def_readwrite("width", &deme::SnapshotOptions::width, "Image width (pixels).")
        .def_readwrite("height", &deme::SnapshotOptions::height, "Image height (pixels).")
        .def_readwrite("direction", &deme::SnapshotOptions::direction, "Viewing direction, into the scene.")
        .def_readwrite("up", &deme::SnapshotOptions::up, "World direction pointing up in the picture.")
        .def_readwrite("boxMin", &deme::SnapshotOptions::boxMin, "Zoom box, low corner.")
        .def_readwrite("boxMax", &deme::SnapshotOptions::boxMax, "Zoom box, high corner (empty box: everything).")
        .def_readwrite("colorBy", &deme::SnapshotOptions::colorBy,
                       "\"speed\", \"height\", \"family\", \"none\" or an owner wildcard's name.")
        .def_readwrite("colorMin", &deme::SnapshotOptions::colorMin, "Colour map low end (NaN: from the data).")
        .def_readwrite("colorMax", &deme::SnapshotOptions::colorMax, "Colour map high end (NaN: from the data).")
        .def_readwrite("colorBar", &deme::SnapshotOptions::colorBar, "Draw a colour bar or the families' legend.")
        .def_readwrite("background", &deme::SnapshotOptions::background, "Background colour (r, g, b), 0-255.")
        .def_readwrite("grainColor", &deme::SnapshotOptions::grainColor, "Grain colour for colorBy \"none\".")
        .def_readwrite("meshColor", &deme::SnapshotOptions::meshColor, "Mesh colour.");
    py::class_<deme::RunProgress>(m, "RunProgress", "Where a DoDynamics call stands (progress callbacks)")
        .def_readonly("stepsDone", &deme::RunProgress::stepsDone)
        .def_readonly("stepsTotal", &deme::RunProgress::stepsTotal)
        .def_readonly("simTime", &deme::RunProgress::simTime)
        .def_readonly("simTimeEnd", &deme::RunProgress::simTimeEnd)
        .def_readonly("wallSeconds", &deme::RunProgress::wallSeconds)
        .def_readonly("spheres", &deme::RunProgress::spheres)
        .def_readonly("finished", &deme::RunProgress::finished);
    py::class_<deme::RunSummary>(m, "RunSummary", "What the last DoDynamics call did and cost")
        .def_readonly("wallSeconds", &deme::RunSummary::wallSeconds)
        .def_readonly("simSeconds", &deme::RunSummary::simSeconds)
        .def_readonly("steps", &deme::RunSummary::steps)
        .def_readonly("spheres", &deme::RunSummary::spheres)
        .def_readonly("sphereStepsPerSecond", &deme::RunSummary::sphereStepsPerSecond)
        .def_readonly("contactsPerSphere", &deme::RunSummary::contactsPerSphere)
        .def_readonly("peakHostBytes", &deme::RunSummary::peakHostBytes)
        .def_readonly("onGpu", &deme::RunSummary::onGpu)
        .def_readonly("deviceBytes", &deme::RunSummary::deviceBytes)
        .def_readonly("deviceBytesPeak", &deme::RunSummary::deviceBytesPeak);
}

}  // namespace

void export_output(py::module_& m, py::class_<PySolver>& c) {
    exportStructs(m);
    c.def("SetVTUEncoding", &D::SetVTUEncoding, py::arg("encoding"),
          "VTU data: \"appended\" (raw binary, default) or \"base64\".")
        .def("SetVTUCompression", &D::SetVTUCompression, py::arg("compression"), "\"none\" (default) or \"zlib\".")
        .def("SetOutputSeries", &D::SetOutputSeries, py::arg("kind"), py::arg("pvdPath"),
             "Adds every later VTU file of kind (spheres, clumps, contacts, meshes) to a ParaView .pvd series.")
        .def(
            "FlushOutput", [](const S& s) { s.runWithoutGilConst([&] { s.FlushOutput(); }); },
            "Waits for the files being written; raises deme.Error if one failed.")
        .def(
            "WriteSnapshot", [](const S& s, const std::string& path) { s.WriteSnapshot(path); }, py::arg("path"),
            "A PNG picture of the spheres and meshes, rendered on the CPU.")
        .def(
            "WriteSnapshot",
            [](const S& s, const std::string& path, const deme::SnapshotOptions& o) { s.WriteSnapshot(path, o); },
            py::arg("path"), py::arg("options"), "The same with SnapshotOptions.")
        .def("SetProgressReport", &D::SetProgressReport, py::arg("enable"), py::arg("intervalSeconds") = 5.0,
             "The progress line of long DoDynamics calls (INFO verbosity and above).")
        .def(
            "SetProgressCallback",
            [](S& s, py::object callback) {
                if (callback.is_none()) {
                    s.SetProgressCallback(nullptr);
                    return;
                }
                // Called between steps while the GIL is released: take it back for the call. An
                // exception the callback raises stops the call there and comes out of DoDynamics.
                s.SetProgressCallback([callback](const deme::RunProgress& p) {
                    py::gil_scoped_acquire gil;
                    callback(p);
                });
            },
            py::arg("callback"), "A callable given a RunProgress as long DoDynamics calls go on (None removes it).")
        .def("GetRunSummary", &D::GetRunSummary, "What the last DoDynamics call did and cost (a RunSummary).");
}

}  // namespace deme_py
