// DEMTracker: read and steer an owner, or each clump of a batch, while the simulation runs. The
// per-owner calls take an offset within the tracked batch; the batch calls (Positions(), ...)
// return one numpy row per owner, in offset order, filled by the C++ batch forms in one pass.
#include "Exports.h"

#include <deme/Tracker.h>

namespace deme_py {

namespace {

using Tr = deme::DEMTracker;

// An (n, Cols) float32 array filled by one of the tracker's batch forms.
template <class V, size_t Cols>
py::array_t<float> batch(const Tr& t, void (Tr::*fill)(V*) const) {
    py::array_t<float> out(std::vector<py::ssize_t>{(py::ssize_t)t.GetNumOwners(), (py::ssize_t)Cols});
    (t.*fill)(reinterpret_cast<V*>(out.mutable_data()));
    return out;
}

}  // namespace

void export_trackers(py::module_& m) {
    py::class_<Tr, std::shared_ptr<Tr>>(m, "DEMTracker",
                                        "Reads and steers tracked owners (from DEMSolver.Track); valid after Initialize")
        .def("Pos", &Tr::Pos, py::arg("offset") = 0, "Position (global).")
        .def("Vel", &Tr::Vel, py::arg("offset") = 0, "Velocity (global).")
        .def("AngVelLocal", &Tr::AngVelLocal, py::arg("offset") = 0, "Angular velocity in the body frame.")
        .def("AngVelGlobal", &Tr::AngVelGlobal, py::arg("offset") = 0, "Angular velocity in the global frame.")
        .def("OriQ", &Tr::OriQ, py::arg("offset") = 0, "Orientation quaternion [x, y, z, w].")
        .def("Mass", &Tr::Mass, py::arg("offset") = 0, "Mass.")
        .def("MOI", &Tr::MOI, py::arg("offset") = 0, "Principal moments of inertia (body frame).")
        .def("GetFamily", &Tr::GetFamily, py::arg("offset") = 0, "Family.")
        .def("ContactAcc", &Tr::ContactAcc, py::arg("offset") = 0, "Contact force over mass, last step.")
        .def("ContactAngAccLocal", &Tr::ContactAngAccLocal, py::arg("offset") = 0,
             "Contact torque in the body frame over MOI, last step.")
        .def("ContactForce", &Tr::ContactForce, py::arg("offset") = 0, "Contact force (global), last step.")
        .def("ContactTorque", &Tr::ContactTorque, py::arg("offset") = 0, "Contact torque (global), last step.")
        .def("SetPos", &Tr::SetPos, py::arg("pos"), py::arg("offset") = 0, "Moves the owner.")
        .def("SetVel", &Tr::SetVel, py::arg("vel"), py::arg("offset") = 0, "Sets the velocity (global).")
        .def("SetAngVel", &Tr::SetAngVel, py::arg("angVelLocal"), py::arg("offset") = 0,
             "Sets the angular velocity (body frame).")
        .def("SetOriQ", &Tr::SetOriQ, py::arg("q"), py::arg("offset") = 0, "Sets the orientation [x, y, z, w].")
        .def("AddAcc", &Tr::AddAcc, py::arg("acc"), py::arg("offset") = 0,
             "Extra acceleration on every step of the next DoDynamics call.")
        .def("AddAngAcc", &Tr::AddAngAcc, py::arg("angAccLocal"), py::arg("offset") = 0,
             "Extra angular acceleration (body frame) on every step of the next DoDynamics call.")
        .def("SetOwnerWildcardValue", &Tr::SetOwnerWildcardValue, py::arg("name"), py::arg("value"),
             py::arg("offset") = 0, "Sets an owner wildcard of the force model for this owner.")
        .def("GetOwnerWildcardValue", &Tr::GetOwnerWildcardValue, py::arg("name"), py::arg("offset") = 0,
             "An owner wildcard of the force model for this owner.")
        .def("GetNumOwners", &Tr::GetNumOwners, "Number of tracked owners.")
        .def("GetOwnerID", &Tr::GetOwnerID, py::arg("offset") = 0, "Owner id in user order.")
        // Batch forms.
        .def(
            "Positions", [](const Tr& t) { return batch<deme::float3, 3>(t, &Tr::Positions); },
            "Positions of all tracked owners, (n, 3) float32 in offset order.")
        .def(
            "Velocities", [](const Tr& t) { return batch<deme::float3, 3>(t, &Tr::Velocities); },
            "Velocities (global) of all tracked owners, (n, 3) float32.")
        .def(
            "AngularVelocities", [](const Tr& t) { return batch<deme::float3, 3>(t, &Tr::AngularVelocities); },
            "Angular velocities in the global frame, (n, 3) float32.")
        .def(
            "OriQs", [](const Tr& t) { return batch<deme::float4, 4>(t, &Tr::OriQs); },
            "Orientations, (n, 4) float32 with columns x, y, z, w.")
        .def(
            "ContactForces", [](const Tr& t) { return batch<deme::float3, 3>(t, &Tr::ContactForces); },
            "Contact forces (global) of the last step, (n, 3) float32.")
        .def(
            "ContactTorques", [](const Tr& t) { return batch<deme::float3, 3>(t, &Tr::ContactTorques); },
            "Contact torques (global) of the last step, (n, 3) float32.")
        .def("SetPositions", py::overload_cast<const std::vector<deme::float3>&>(&Tr::SetPositions),
             py::arg("positions"), "Moves all tracked owners, (n, 3); all rows checked before any is applied.")
        .def("SetVelocities", py::overload_cast<const std::vector<deme::float3>&>(&Tr::SetVelocities),
             py::arg("velocities"), "Sets all velocities (global), (n, 3); all rows checked first.");
}

}  // namespace deme_py
