// DEMSolver, scenes that change while they run (docs/scene-changes.md): clumps added after
// Initialize (AddClumps, then UpdateClumps), clumps removed by family or when they leave the domain.
#include "Exports.h"
#include "PySolver.h"

namespace deme_py {

void export_scene_edits(py::class_<PySolver>& c) {
    using D = deme::DEMSolver;
    c.def("UpdateClumps", &D::UpdateClumps,
          "Puts the batches added by AddClumps after Initialize into the simulation (between DoDynamics "
          "calls; DoDynamics with batches waiting raises deme.Error). New clumps get ids after all ids so far.")
        .def("RemoveClumpsInFamily", &D::RemoveClumpsInFamily, py::arg("family"),
             "Removes every clump of the family now, with its contacts; returns how many. Other ids stay.")
        .def("SetDomainExitPolicy", &D::SetDomainExitPolicy, py::arg("policy"),
             "\"error\" (default): a clump leaving the domain stops the run; \"remove\": it leaves the run "
             "at that step and is removed from the state by the end of the DoDynamics call.")
        .def("GetNumRemovedClumps", &D::GetNumRemovedClumps, "Clumps removed since Initialize.")
        .def("GetRemovedMass", &D::GetRemovedMass, "Total mass of the clumps removed since Initialize.");
}

}  // namespace deme_py
