// DEMSolver, part 2: the scene. Materials and force models, the domain and analytical boundaries,
// meshes, clump templates and clumps, families, trackers and inspectors.
#include "Exports.h"
#include "PySolver.h"

namespace deme_py {

namespace {

using S = PySolver;
using D = deme::DEMSolver;
using MatPtr = std::shared_ptr<deme::DEMMaterial>;
using TmplPtr = std::shared_ptr<deme::DEMClumpTemplate>;

void exportMaterialsAndModels(py::class_<S>& c) {
    c.def("LoadMaterial", &D::LoadMaterial, py::arg("props"),
          "A material from a dict of properties, e.g. {\"E\": 1e8, \"nu\": 0.3, \"CoR\": 0.5, \"mu\": 0.5, \"Crr\": 0}.")
        .def("SetMaterialPropertyPair", &D::SetMaterialPropertyPair, py::arg("name"), py::arg("a"), py::arg("b"),
             py::arg("value"), "The value of a per-pair property (CoR, mu, Crr...) between two materials.")
        .def("UseFrictionalHertzianModel", &D::UseFrictionalHertzianModel,
             "The default history-based Hertz-Mindlin model.")
        .def("UseFrictionlessHertzianModel", &D::UseFrictionlessHertzianModel, "Hertz normal force only.")
        .def("DefineContactForceModel", &D::DefineContactForceModel, py::arg("code"),
             "A custom model: C++ statements run for every contact pair, compiled at Initialize.")
        .def("ReadContactForceModel", &D::ReadContactForceModel, py::arg("path"),
             "A custom model read from a file.");
}

void exportDomainAndObjects(py::class_<S>& c) {
    c.def("InstructBoxDomainDimension", py::overload_cast<float, float, float>(&D::InstructBoxDomainDimension),
          py::arg("x"), py::arg("y"), py::arg("z"), "Box of size x * y * z centred on the origin.")
        .def("InstructBoxDomainDimension",
             py::overload_cast<const std::pair<float, float>&, const std::pair<float, float>&,
                               const std::pair<float, float>&>(&D::InstructBoxDomainDimension),
             py::arg("x"), py::arg("y"), py::arg("z"), "Box spanning (lo, hi) ranges along x, y and z.")
        .def("InstructBoxDomainPeriodicity", &D::InstructBoxDomainPeriodicity, py::arg("axes"),
             "Periodic boundaries along the axes named (\"x\", \"xy\", \"xyz\"...; \"\" for none): a grain leaving "
             "through one face enters through the other (docs/periodic.md).")
        .def("SetPeriodicShear", &D::SetPeriodicShear, py::arg("rate"),
             "A sheared periodic cell (Lees-Edwards): simple shear at rate (1/s) along x, gradient along z; "
             "needs periodic x and z.")
        .def("InstructBoxDomainBoundingBC", &D::InstructBoxDomainBoundingBC, py::arg("type"), py::arg("mat"),
             "Walls on the domain's faces: \"all\", \"top_open\" or \"none\".")
        .def("AddExternalObject", &D::AddExternalObject, "A new external object (add planes and cylinders to it).")
        .def("AddBCPlane", &D::AddBCPlane, py::arg("pos"), py::arg("normal"), py::arg("mat"),
             "A one-plane external object.")
        .def("AddWavefrontMeshObject",
             py::overload_cast<const std::string&, const MatPtr&>(&D::AddWavefrontMeshObject), py::arg("objFile"),
             py::arg("mat"), "Loads a Wavefront OBJ file as one rigid mesh owner.")
        .def("AddWavefrontMeshObject", py::overload_cast<const deme::DEMMeshConnected&>(&D::AddWavefrontMeshObject),
             py::arg("mesh"), "Adds a mesh built in code (its material must be set).");
}

void exportClumps(py::class_<S>& c) {
    c.def("LoadClumpType",
          py::overload_cast<float, const deme::float3&, const std::string&, const MatPtr&>(&D::LoadClumpType),
          py::arg("mass"), py::arg("moi"), py::arg("csvFile"), py::arg("mat"),
          "A clump template from a CSV of component spheres (columns x, y, z, r).")
        .def("LoadClumpType",
             py::overload_cast<float, const deme::float3&, const std::vector<float>&, const std::vector<deme::float3>&,
                               const MatPtr&>(&D::LoadClumpType),
             py::arg("mass"), py::arg("moi"), py::arg("radii"), py::arg("positions"), py::arg("mat"),
             "A clump template from radii (N,) and positions (N, 3), one material.")
        .def("LoadClumpType",
             py::overload_cast<float, const deme::float3&, const std::vector<float>&, const std::vector<deme::float3>&,
                               const std::vector<MatPtr>&>(&D::LoadClumpType),
             py::arg("mass"), py::arg("moi"), py::arg("radii"), py::arg("positions"), py::arg("mats"),
             "A clump template from radii and positions, one material per sphere.")
        .def("LoadSphereType", &D::LoadSphereType, py::arg("mass"), py::arg("radius"), py::arg("mat"),
             "A one-sphere clump template.")
        .def("AddClumps", py::overload_cast<const TmplPtr&, const std::vector<deme::float3>&>(&D::AddClumps),
             py::arg("type"), py::arg("positions"), "Clumps of one template at positions (N, 3); returns the batch.")
        .def("AddClumps",
             py::overload_cast<const std::vector<TmplPtr>&, const std::vector<deme::float3>&>(&D::AddClumps),
             py::arg("types"), py::arg("positions"), "Clumps with one template each at positions (N, 3).");
}

void exportFamilies(py::class_<S>& c) {
    c.def("SetFamilyFixed", &D::SetFamilyFixed, py::arg("family"), "The family's owners never move.")
        .def("SetFamilyPrescribedLinVel", &D::SetFamilyPrescribedLinVel, py::arg("family"), py::arg("vx"),
             py::arg("vy"), py::arg("vz"), "Velocity as expressions of time t (\"none\" leaves a component free).")
        .def("SetFamilyPrescribedAngVel", &D::SetFamilyPrescribedAngVel, py::arg("family"), py::arg("wx"),
             py::arg("wy"), py::arg("wz"), "Angular velocity (body frame) as expressions of time t.")
        .def("DisableContactBetweenFamilies", &D::DisableContactBetweenFamilies, py::arg("a"), py::arg("b"),
             "No contacts between families a and b.")
        .def("EnableContactBetweenFamilies", &D::EnableContactBetweenFamilies, py::arg("a"), py::arg("b"),
             "Contacts between families a and b again.")
        .def("ChangeFamily", &D::ChangeFamily, py::arg("from_"), py::arg("to"),
             "Moves every owner of family from_ to family to.");
}

void exportTrackersAndInspectors(py::class_<S>& c) {
    // A tracker or inspector reads the solver's state: it keeps the solver alive.
    c.def("Track", py::overload_cast<const std::shared_ptr<deme::DEMClumpBatch>&>(&D::Track), py::arg("batch"),
          py::keep_alive<0, 1>(), "A tracker of every clump of a batch.")
        .def("Track", py::overload_cast<const std::shared_ptr<deme::DEMExternObj>&>(&D::Track), py::arg("obj"),
             py::keep_alive<0, 1>(), "A tracker of an external object.")
        .def("Track", py::overload_cast<const std::shared_ptr<deme::DEMMeshConnected>&>(&D::Track),
             py::arg("mesh"), py::keep_alive<0, 1>(), "A tracker of a mesh.")
        .def("CreateInspector", py::overload_cast<const std::string&>(&D::CreateInspector), py::arg("kind"),
             py::keep_alive<0, 1>(),
             "clump_max_z, clump_min_z, clump_max_absv, clump_kinetic_energy, clump_mass or num_contacts.")
        .def("CreateInspector",
             py::overload_cast<const std::string&, const deme::float3&, const deme::float3&>(&D::CreateInspector),
             py::arg("kind"), py::arg("lo"), py::arg("hi"), py::keep_alive<0, 1>(),
             "An inspector over the box region [lo, hi]: \"stress\" (GetStress(), GetValue() the mean normal "
             "stress, compression positive).");
}

}  // namespace

void export_solver_scene(py::class_<PySolver>& c) {
    exportMaterialsAndModels(c);
    exportDomainAndObjects(c);
    exportClumps(c);
    exportFamilies(c);
    exportTrackersAndInspectors(c);
}

}  // namespace deme_py
