// Legacy-VTK output of triangle meshes (mesh walls, mixer blades) for ParaView.
#pragma once

#include <string>
#include <vector>

#include <deme/Mesh.h>
#include <deme/VectorTypes.h>

namespace deme {

// Writes a legacy VTK ASCII POLYDATA file: "# vtk DataFile Version 3.0" header, POINTS as float,
// POLYGONS "3 i j k", then CELL_DATA with an int scalar "owner" (one value per triangle).
// Numbers are written independently of the C locale (a ',' decimal separator would break ParaView).
// Written to a temporary name and renamed (io/AtomicFile.h).
// Throws deme::Error via throwError(call, ...) naming the path if the file cannot be written, and before
// creating the file if triangleOwner.size() != triangles.size() or a triangle indexes outside points.
void writeVtkTriangles(const std::string& path, const std::vector<double3>& points, const std::vector<int3>& triangles,
                       const std::vector<int>& triangleOwner, const std::string& call);

}  // namespace deme
