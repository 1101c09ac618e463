// Checkpoint and restart (docs/checkpoint.md): DEMSolver.WriteCheckpoint and ReadCheckpoint. Both
// release the GIL while the file is written or read (large runs make large files).
#include "Exports.h"
#include "PySolver.h"

namespace deme_py {

void export_checkpoint(py::class_<PySolver>& c) {
    c.def(
         "WriteCheckpoint",
         [](const PySolver& s, const std::string& path) { s.runWithoutGilConst([&] { s.WriteCheckpoint(path); }); },
         py::arg("path"),
         "Writes everything the run needs to go on to path (temporary name, then rename: a crash keeps the "
         "previous file).")
        .def(
            "ReadCheckpoint", [](PySolver& s, const std::string& path) { s.runWithoutGil([&] { s.ReadCheckpoint(path); }); },
            py::arg("path"),
            "After Initialize() of the same scene: continues the run the checkpoint was taken of. A bad file "
            "raises deme.Error (truncated, corrupted, wrong version, another scene) and changes nothing.");
}

}  // namespace deme_py
