// GetDEMEDataFile: the data files shipped with the package (deme/data beside the extension).
#include "Exports.h"

#include <deme/DataFiles.h>

namespace deme_py {

void export_data_files(py::module_& m) {
    m.def("GetDEMEDataFile", &deme::GetDEMEDataFile, py::arg("relative"),
          "Absolute path of a shipped data file, e.g. \"mesh/internal_mixer.obj\"; deme.Error if none has it.");
    m.def("GetDEMEDataDirs", &deme::GetDEMEDataDirs, "The folders GetDEMEDataFile searches, in its order.");
}

}  // namespace deme_py
