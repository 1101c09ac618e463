// One export function per part of the public C++ API; module.cpp calls them in dependency order
// (a class must be registered before a signature that names it is shown in help()).
#pragma once

#include "Casters.h"

namespace deme_py {

class PySolver;

void export_errors(py::module_& m);
void export_types(py::module_& m);  // constants and enums of VariableTypes.h, RayleighTime
void export_data_files(py::module_& m);
void export_materials(py::module_& m);
void export_force_models(py::module_& m);
void export_templates(py::module_& m);  // clump templates and batches
void export_objects(py::module_& m);    // external objects and meshes
void export_trackers(py::module_& m);
void export_inspectors(py::module_& m);
void export_samplers(py::module_& m);
void export_solver(py::module_& m);  // DEMSolver: settings, scene, running, output
void export_solver_scene(py::class_<PySolver>& cls);
void export_solver_wildcards(py::class_<PySolver>& cls);
void export_scene_edits(py::class_<PySolver>& cls);  // clumps added and removed during a run
void export_output(py::module_& m, py::class_<PySolver>& cls);  // VTU/PVD, snapshots, progress
void export_checkpoint(py::class_<PySolver>& cls);                // WriteCheckpoint, ReadCheckpoint
void export_family_changes(py::module_& m, py::class_<PySolver>& cls);  // ChangeFamilyWhen, tracker families

}  // namespace deme_py
