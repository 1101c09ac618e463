// deme::Error reaches Python as deme.Error, a RuntimeError with the C++ message (which names the
// call, and file:line for files).
#include "Exports.h"

#include <deme/Error.h>

namespace deme_py {

void export_errors(py::module_& m) {
    py::register_exception<deme::Error>(m, "Error", PyExc_RuntimeError);
    m.attr("Error").attr("__doc__") =
        "Bad input or a failed run: the message starts with the C++ call's name (and file:line for files).";
}

}  // namespace deme_py
