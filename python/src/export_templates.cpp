// DEMClumpTemplate (a shape made of spheres, with its mass properties) and DEMClumpBatch (the
// clumps one AddClumps call added). Batch setters take one value for all clumps or one per clump
// as an (N, 3) / (N, 4) array; getters return arrays in the batch's order.
#include "Exports.h"

#include <deme/ClumpTemplate.h>

namespace deme_py {

void export_templates(py::module_& m) {
    using T = deme::DEMClumpTemplate;
    py::class_<T, std::shared_ptr<T>>(m, "DEMClumpTemplate",
                                      "A clump shape: component spheres in the principal frame, mass and MOI")
        .def_readwrite("mass", &T::mass, "Mass (kg).")
        .def_readwrite("MOI", &T::MOI, "Principal moments of inertia about the principal axes.")
        .def_readwrite("radii", &T::radii, "Component sphere radii (N,).")
        .def_readwrite("relPos", &T::relPos, "Component sphere centres relative to the centre of mass (N, 3).")
        .def_readwrite("materials", &T::materials, "One material per component sphere.")
        .def("Scale", &T::Scale, py::arg("s"), "Scales lengths by s, mass by s^3 and MOI by s^5.")
        .def("GetNumSpheres", &T::GetNumSpheres, "Number of component spheres.")
        .def("GetExtent", &T::GetExtent, "Largest distance from the centre to any point of the spheres.");

    using B = deme::DEMClumpBatch;
    py::class_<B, std::shared_ptr<B>>(m, "DEMClumpBatch", "The clumps added by one AddClumps call")
        .def(py::init<std::vector<std::shared_ptr<T>>, std::vector<deme::float3>>(), py::arg("types"),
             py::arg("positions"), "A batch not yet added to a solver (AddClumps makes the ones it runs).")
        .def(py::init<std::shared_ptr<T>, std::vector<deme::float3>>(), py::arg("type"), py::arg("positions"),
             "A batch of clumps of one template, not yet added to a solver.")
        .def("GetNumClumps", &B::GetNumClumps, "Number of clumps in the batch.")
        .def("SetVel", py::overload_cast<const deme::float3&>(&B::SetVel), py::arg("v"), "One velocity for all clumps.")
        .def("SetVel", py::overload_cast<const std::vector<deme::float3>&>(&B::SetVel), py::arg("v"),
             "One velocity per clump, (N, 3).")
        .def("SetAngVel", py::overload_cast<const deme::float3&>(&B::SetAngVel), py::arg("w"),
             "One angular velocity (local frame) for all clumps.")
        .def("SetAngVel", py::overload_cast<const std::vector<deme::float3>&>(&B::SetAngVel), py::arg("w"),
             "One angular velocity (local frame) per clump, (N, 3).")
        .def("SetOriQ", py::overload_cast<const deme::float4&>(&B::SetOriQ), py::arg("q"),
             "One orientation quaternion [x, y, z, w] for all clumps.")
        .def("SetOriQ", py::overload_cast<const std::vector<deme::float4>&>(&B::SetOriQ), py::arg("q"),
             "One quaternion per clump, (N, 4) with columns x, y, z, w.")
        .def("SetFamily", py::overload_cast<unsigned int>(&B::SetFamily), py::arg("family"),
             "One family for all clumps.")
        .def("SetFamily", py::overload_cast<const std::vector<unsigned int>&>(&B::SetFamily), py::arg("families"),
             "One family per clump.")
        .def("GetTypes", &B::GetTypes, "The template of each clump (a new list).")
        .def("GetType", &B::GetType, py::arg("i"), "Clump i's template.")
        .def("GetDistinctTypes", &B::GetDistinctTypes,
             "The templates the batch uses, each once, in the order of their first clump.")
        .def("GetPositions", &B::GetPositions, "Initial positions, (N, 3); an error once Initialize or UpdateClumps took the batch.")
        .def("GetVelocities", &B::GetVelocities, "Initial velocities, (N, 3); until Initialize or UpdateClumps.")
        .def("GetAngVelocities", &B::GetAngVelocities, "Initial angular velocities (local frame), (N, 3); until Initialize or UpdateClumps.")
        .def("GetOriQs", &B::GetOriQs, "Initial orientations, (N, 4) with columns x, y, z, w; until Initialize or UpdateClumps.")
        .def(
            "GetFamilies",
            [](const B& b) {
                const auto& f = b.GetFamilies();
                py::array_t<uint8_t> out((py::ssize_t)f.size());
                if (!f.empty()) std::memcpy(out.mutable_data(), f.data(), f.size());
                return out;
            },
            "Families, (N,) uint8; until Initialize or UpdateClumps.")
        .def("GetHostBytes", &B::GetHostBytes,
             "Host bytes of the batch's own arrays (initial values until Initialize, then its template index).")
        .def("GetOwnerOffset", &B::GetOwnerOffset,
             "Owner id of the batch's first clump (valid after Initialize).");
}

}  // namespace deme_py
