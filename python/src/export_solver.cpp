// DEMSolver, part 1: construction, messages and output, time stepping and detection settings,
// running, queries. The scene (materials, objects, clumps, families, trackers) is bound in
// export_solver_scene.cpp, wildcards and persistent contacts in export_solver_wildcards.cpp.
#include "Exports.h"
#include "PySolver.h"

namespace deme_py {

namespace {

using S = PySolver;
using D = deme::DEMSolver;

void exportMessagesAndOutput(py::class_<S>& c) {
    c.def("SetVerbosity", &D::SetVerbosity, py::arg("level"),
          "QUIET, ERROR, WARNING, INFO or STEP_METRIC (each includes the ones before it).")
        .def("SetOutputFormat", &D::SetOutputFormat, py::arg("format"),
             "Sphere, clump and contact files: \"CSV\" (default) or \"VTU\" (ParaView).")
        .def("SetOutputContent", py::overload_cast<const std::string&>(&D::SetOutputContent), py::arg("content"),
             "Extra sphere-file columns in one string (\"ABSV VEL\"): XYZ, ABSV, VEL, ANG_VEL, FAMILY, OWNER, MAT, "
             "QUAT.")
        .def("SetOutputContent", py::overload_cast<const std::vector<std::string>&>(&D::SetOutputContent),
             py::arg("content"), "Extra sphere-file columns as a list of names.")
        .def("SetMeshOutputFormat", &D::SetMeshOutputFormat, py::arg("format"),
             "Mesh file format: \"VTK\" (legacy, default) or \"VTU\".")
        .def("WriteMeshFile", &D::WriteMeshFile, py::arg("path"),
             "Every mesh in its current pose, one file (VTK or VTU).")
        .def("WriteSphereFile", &D::WriteSphereFile, py::arg("path"),
             "One row (CSV) or point (VTU) per sphere; written by the writer thread.")
        .def("WriteClumpFile", &D::WriteClumpFile, py::arg("path"), "One row or point per clump.")
        .def("WriteStressField", &D::WriteStressField, py::arg("path"), py::arg("lo"), py::arg("hi"), py::arg("nx"),
             py::arg("ny"), py::arg("nz"),
             "The coarse-grained stress of the grains over the box [lo, hi] in nx x ny x nz cells: one row per "
             "cell (CSV or VTU, as the sphere files).")
        .def("WriteContactFile", &D::WriteContactFile, py::arg("path"),
             "One row or point per geometry pair in contact.")
        .def("ShowTimingStats", &D::ShowTimingStats, "Prints the time per phase and the throughput.")
        .def("GetDeviceMemUsage", &D::GetDeviceMemUsage, "Bytes of GPU memory the engine holds (0 on the CPU).")
        .def("ShowMemStats", &D::ShowMemStats, "Prints the memory report.")
        .def(
            "GetMemoryStats",
            [](const S& d) {
                const deme::MemoryStats m = d.GetMemoryStats();
                py::dict device, devicePeak, host, estimate;
                for (int g = 0; g < deme::NUM_MEMORY_GROUPS; g++) {
                    const char* key = deme::memoryGroupKey((deme::MemoryGroup)g);
                    device[key] = m.deviceBytes[g];
                    devicePeak[key] = m.devicePeakBytes[g];
                    host[key] = m.hostBytes[g];
                    estimate[key] = m.estimatedBytes[g];
                }
                py::dict r;
                r["spheres"] = m.spheres;
                r["device"] = device;
                r["host"] = host;
                r["device_total"] = m.deviceTotal();
                r["device_peak"] = devicePeak;
                r["device_peak_total"] = m.devicePeakTotal();
                r["host_total"] = m.hostTotal();
                r["estimate"] = estimate;
                r["estimate_total"] = m.estimatedTotal();
                r["estimated_pairs"] = m.estimatedPairs;
                return r;
            },
            "Memory by array group: {'spheres', 'device': {group: bytes}, 'host': {group: bytes}, 'device_total', "
            "'host_total', 'device_peak': {group: bytes}, 'device_peak_total', 'estimate': {group: bytes}, "
            "'estimate_total', 'estimated_pairs'}; device_peak: each group's GPU memory when the process's total "
            "was last at its peak (zeros on 'cpu'); groups owner_state, "
            "geometry, contacts_and_history, wildcards, detection_scratch, output_staging, step_scratch. The "
            "estimate is what Initialize expected the run to hold where its steps keep their arrays (the GPU's on "
            "'cuda', the host's on 'cpu'), with its first contact set of estimated_pairs pairs.")
        .def("ShowMemoryStats", &D::ShowMemoryStats, "Prints memory by array group, in MiB and bytes per sphere.")
        .def("ClearThreadCollaborationStats", &D::ClearThreadCollaborationStats,
             "Starts the collaboration counters and GetDynamicsWaitShare afresh (after a settling phase).")
        .def("ShowThreadCollaborationStats", &D::ShowThreadCollaborationStats,
             "Prints how the kinematics and dynamics sides worked together.")
        .def("GetDynamicsWaitShare", &D::GetDynamicsWaitShare,
             "Share (0..1) of the step loop's wall time the dynamics side waited for a contact set.")
        .def("GetNumAsyncContactSetUpdates", &D::GetNumAsyncContactSetUpdates,
             "Contact sets detected asynchronously and installed.");
}

void exportTimeStepping(py::class_<S>& c) {
    c.def("SetInitTimeStep", &D::SetInitTimeStep, py::arg("dt"), "The time step (s).")
        .def("UpdateStepSize", &D::UpdateStepSize, py::arg("dt"), "Changes the time step between DoDynamics calls.")
        .def("SetGravitationalAcceleration", &D::SetGravitationalAcceleration, py::arg("g"), "Gravity (m/s^2).")
        .def("SetErrorOutVelocity", &D::SetErrorOutVelocity, py::arg("v"),
             "A run whose fastest owner exceeds v stops with deme.Error naming it.")
        .def("SetMaxVelocity", &D::SetMaxVelocity, py::arg("v"), "Expected largest speed, sizes the contact margin.")
        .def("SetExpandSafetyMultiplier", &D::SetExpandSafetyMultiplier, py::arg("m"), "Contact margin multiplier.")
        .def("SetExpandSafetyAdder", &D::SetExpandSafetyAdder, py::arg("a"), "Contact margin adder (m).")
        .def("SetCDUpdateFreq", &D::SetCDUpdateFreq, py::arg("n"), "n_max: the most steps one contact set serves.")
        .def("SetCDMaxUpdateFreq", &D::SetCDMaxUpdateFreq, py::arg("n"), "Cap for the adaptive n_max.")
        .def("UseAdaptiveUpdateFreq", &D::UseAdaptiveUpdateFreq, "Adapt n_max from the kinematics latency.")
        .def("DisableAdaptiveUpdateFreq", &D::DisableAdaptiveUpdateFreq, "Keep n_max fixed.")
        .def("GetUpdateFreq", &D::GetUpdateFreq, "The current n_max.")
        .def("SetSynchronousContactDetection", &D::SetSynchronousContactDetection, py::arg("sync"),
             "True: detect on the dynamics thread every n_max steps; False: on the kinematics thread.")
        .def("UsesAsyncContactDetection", &D::UsesAsyncContactDetection, "Whether detection runs on its own thread.")
        .def("SetFamilyExtraMargin", &D::SetFamilyExtraMargin, py::arg("family"), py::arg("margin"),
             "Extra contact margin for the geometries of a family's owners.")
        .def("SetInitBinSize", &D::SetInitBinSize, py::arg("size"), "Bin size of contact detection.")
        .def("SetForceCalcThreadsPerBlock", &D::SetForceCalcThreadsPerBlock, py::arg("n"),
             "Block size of the GPU force kernel, 1..1024; by default 128 below 2^18 contacts, 256 above "
             "(no effect on the CPU).")
        .def("SetCPUThreads", &D::SetCPUThreads, py::arg("n"), "CPU threads of the parallel loops.")
        .def("SetBackend", &D::SetBackend, py::arg("backend"),
             "\"cpu\", \"cuda\" or \"auto\" (default: $DEME_BACKEND, else auto).")
        .def("GetBackend", &D::GetBackend, "The backend in effect after Initialize: \"cpu\" or \"cuda\".");
}

void exportRunning(py::class_<S>& c) {
    c.def(
         "Initialize", [](S& s) { s.runWithoutGil([&] { s.Initialize(); }); },
         "Builds the simulation (compiles a custom force model); releases the GIL meanwhile.")
        .def(
            "DoDynamics", [](S& s, double t) { s.runInterruptible([&] { s.DoDynamics(t); }); }, py::arg("duration"),
            "Advances by duration (whole steps); releases the GIL, Ctrl-C stops it at a step boundary.")
        .def(
            "DoDynamicsThenSync", [](S& s, double t) { s.runInterruptible([&] { s.DoDynamicsThenSync(t); }); },
            py::arg("duration"), "DoDynamics, then lets contact detection catch up.")
        .def(
            "DoStepDynamics", [](S& s) { s.runInterruptible([&] { s.DoStepDynamics(); }); }, "Advances one step.")
        .def(
            "SetInterruptCheck", [](S& s, py::object check) { s.setUserInterruptCheck(std::move(check)); },
            py::arg("check"),
            "A callable polled between steps (at most every 50 ms); returning True stops the call. None removes it.")
        .def("WasInterrupted", &D::WasInterrupted, "Whether the last DoDynamics call was stopped early.");
}

void exportQueries(py::class_<S>& c) {
    c.def("GetSimTime", &D::GetSimTime, "Simulated time (s).")
        .def("GetTimeStep", &D::GetTimeStep, "The time step (s).")
        .def("GetNumClumps", &D::GetNumClumps, "Number of clumps.")
        .def("GetNumSpheres", &D::GetNumSpheres, "Number of spheres.")
        .def("GetNumContacts", &D::GetNumContacts, "Geometry pairs in contact (overlap > 0) after the last step.")
        .def("GetAvgSphContacts", &D::GetAvgSphContacts, "Contacts per sphere.")
        .def("GetGravitationalAcceleration", &D::GetGravitationalAcceleration, "Gravity.");
}

}  // namespace

void export_solver(py::module_& m) {
    py::class_<S> c(m, "DEMSolver", "The simulation: scene set-up, Initialize, then DoDynamics frame by frame");
    c.def(py::init<>(), "A solver (backend as SetBackend says).")
        .def(py::init<unsigned int>(), py::arg("nGPUs"), "A solver on the first nGPUs GPUs.")
        .def(py::init<const std::vector<int>&>(), py::arg("deviceIds"), "A solver on the GPUs with these ids.");
    exportMessagesAndOutput(c);
    exportTimeStepping(c);
    exportRunning(c);
    exportQueries(c);
    export_solver_scene(c);
    export_solver_wildcards(c);
    export_scene_edits(c);
    export_output(m, c);
    export_checkpoint(c);
    export_family_changes(m, c);
}

}  // namespace deme_py
