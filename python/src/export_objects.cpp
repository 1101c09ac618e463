// External objects (analytical planes and cylinders) and triangle meshes: owners the grains meet.
#include "Exports.h"

#include <deme/ExternalObject.h>
#include <deme/Mesh.h>

namespace deme_py {

void export_objects(py::module_& m) {
    using E = deme::DEMExternObj;
    py::class_<E, std::shared_ptr<E>> obj(m, "DEMExternObj",
                                          "An owner made of analytical components (planes, cylinders)");
    py::class_<E::Component>(obj, "Component", "One analytical component, in the object's frame")
        .def_readonly("type", &E::Component::type, "ANAL_PLANE or ANAL_CYLINDER.")
        .def_readonly("pos", &E::Component::pos, "A point of the surface.")
        .def_readonly("dir", &E::Component::dir, "Plane: unit normal towards the grains; cylinder: unit axis.")
        .def_readonly("radius", &E::Component::radius, "Cylinder radius.")
        .def_readonly("inside", &E::Component::inside, "Cylinder: grains inside.")
        .def_readonly("material", &E::Component::material, "The component's material.");
    obj.def(py::init<>(), "An object not yet added to a solver (AddExternalObject makes the ones it runs).")
        .def("AddPlane", &E::AddPlane, py::arg("pos"), py::arg("normal"), py::arg("mat"),
             "Plane through pos; grains live on the side the normal points to.")
        .def("AddCylinder", &E::AddCylinder, py::arg("pos"), py::arg("axis"), py::arg("radius"), py::arg("mat"),
             py::arg("normal_dir") = 0, "Infinite cylinder; normal_dir 0: grains inside, 1: grains outside.")
        .def("SetFamily", &E::SetFamily, py::arg("family"), "The object's family (0..255).")
        .def("SetInitPos", &E::SetInitPos, py::arg("pos"), "Initial position of the object frame.")
        .def("SetInitQuat", &E::SetInitQuat, py::arg("q"), "Initial orientation [x, y, z, w].")
        .def("SetMass", &E::SetMass, py::arg("mass"), "Mass reported to trackers and the force model.")
        .def("SetMOI", &E::SetMOI, py::arg("moi"), "Principal moments reported to trackers.")
        .def("GetComponents", &E::GetComponents, "The components added so far.")
        .def("GetFamily", &E::GetFamily, "The object's family.")
        .def("GetInitPos", &E::GetInitPos, "Initial position.")
        .def("GetInitQuat", &E::GetInitQuat, "Initial orientation [x, y, z, w].")
        .def("GetMass", &E::GetMass, "Mass.")
        .def("GetMOI", &E::GetMOI, "Principal moments of inertia.")
        .def("GetOwnerID", &E::GetOwnerID, "Owner id (valid after Initialize).");

    using M = deme::DEMMeshConnected;
    py::class_<M, std::shared_ptr<M>>(m, "DEMMeshConnected",
                                      "A rigid triangle mesh owner; vertices in its frame (origin = centre of mass)")
        .def(py::init<>(), "An empty mesh.")
        .def(py::init<std::vector<deme::float3>, std::vector<deme::int3>, std::shared_ptr<deme::DEMMaterial>>(),
             py::arg("vertices"), py::arg("faces"), py::arg("mat"),
             "A mesh from vertices (N, 3) and 0-based faces (M, 3) of integers, one material.")
        .def("Scale", py::overload_cast<float>(&M::Scale), py::arg("s"), "Scales the vertices by s.")
        .def("Scale", py::overload_cast<const deme::float3&>(&M::Scale), py::arg("s"), "Scales per axis.")
        .def("SetFamily", &M::SetFamily, py::arg("family"), "The mesh's family (0..255).")
        .def("SetInitPos", &M::SetInitPos, py::arg("pos"), "Initial position of the mesh frame.")
        .def("SetInitQuat", &M::SetInitQuat, py::arg("q"), "Initial orientation [x, y, z, w].")
        .def("SetMass", &M::SetMass, py::arg("mass"), "Makes the mesh a free body of this mass.")
        .def("SetMOI", &M::SetMOI, py::arg("moi"), "Principal moments of inertia.")
        .def("SetMaterial", &M::SetMaterial, py::arg("mat"), "The material of all its triangles.")
        .def("TranslateFrame", &M::TranslateFrame, py::arg("p"),
             "Moves the vertices so that p (mesh frame) becomes the frame's origin.")
        .def("GetNumTriangles", &M::GetNumTriangles, "Number of triangles.")
        .def("GetNumVertices", &M::GetNumVertices, "Number of vertices.")
        .def("GetVertices", &M::GetVertices, "Vertices in the mesh frame, (N, 3) float32.")
        .def("GetFaces", &M::GetFaces, "Faces, (M, 3) int32, 0-based.")
        .def("GetMaterial", &M::GetMaterial, "The material.")
        .def("GetFamily", &M::GetFamily, "The mesh's family.")
        .def("GetInitPos", &M::GetInitPos, "Initial position.")
        .def("GetInitQuat", &M::GetInitQuat, "Initial orientation [x, y, z, w].")
        .def("GetMass", &M::GetMass, "Mass.")
        .def("GetMOI", &M::GetMOI, "Principal moments of inertia.")
        .def("IsFree", &M::IsFree, "Whether forces move it (SetMass was called).")
        .def("GetOwnerID", &M::GetOwnerID, "Owner id (valid after Initialize).");
}

}  // namespace deme_py
