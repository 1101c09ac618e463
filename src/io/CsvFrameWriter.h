// CSV text of a staged frame: a header row of the columns' CSV names, then one row per point.
// Floating-point values as printf's "%.9g" (9 significant digits: exact for a float), written
// with std::to_chars, which is independent of the C locale and several times faster than printf.
#pragma once

#include "io/AtomicFile.h"
#include "io/OutputFrame.h"

namespace deme {

void writeFrameCsv(const OutputFrame& frame, AtomicFile& out);

}  // namespace deme
