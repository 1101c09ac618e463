// The data files shipped with the engine (data/ in the source tree: the mixer mesh and clump
// templates of the paper's listings), found wherever the engine was built or installed.
#pragma once

#include <string>
#include <vector>

namespace deme {

// Absolute path of the data file `relative` (e.g. "mesh/internal_mixer.obj", "clumps/3_clump.csv").
// Looked for, in this order, in
//   1. $DEME_DATA_DIR, if set;
//   2. data/ beside the binary holding the engine (the Python package: <site-packages>/deme/data),
//      and ../share/deme/data from it (an installed program in <prefix>/bin);
//   3. <prefix>/share/deme/data of the configured install prefix;
//   4. data/ of the source tree the engine was built from.
// Throws deme::Error("GetDEMEDataFile: ...") naming the file and the folders searched when none
// has it.
std::string GetDEMEDataFile(const std::string& relative);

// The folders GetDEMEDataFile searches, in its order (existing or not).
std::vector<std::string> GetDEMEDataDirs();

}  // namespace deme
