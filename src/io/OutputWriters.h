// CSV output of spheres, clumps and contacts; columns are documented in README.md.
#pragma once

#include <string>

namespace deme {

class Simulation;

void writeSphereCsv(const Simulation& sim, const std::string& path);
void writeClumpCsv(const Simulation& sim, const std::string& path);
void writeContactCsv(const Simulation& sim, const std::string& path);
void writeMeshVtk(const Simulation& sim, const std::string& path);

}  // namespace deme
