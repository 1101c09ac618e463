// VTK XML UnstructuredGrid (.vtu) of a staged frame, which ParaView, VisIt and meshio open as is:
// the frame's points column as the grid's points (Float64), one VTK_VERTEX cell per point (meshes:
// one VTK_TRIANGLE per 3 points), every other column as a point-data array of its own type
// (vectors as 3-component arrays, quaternions as 4), and the simulated time as the field-data
// array TimeValue. header_type UInt64, so arrays may exceed 4 GiB.
#pragma once

#include "io/AtomicFile.h"
#include "io/OutputFrame.h"

namespace deme {

struct VtuOptions {
    // Appended raw binary (the default: the smallest and fastest to write and to read; the file is
    // XML up to one binary section at its end) or base64 text inside each DataArray (pure text,
    // for tools that need valid XML; a third larger and slower).
    bool base64 = false;
    // zlib compression of each array in 1 MiB blocks (vtkZLibDataCompressor). Off by default:
    // positions and velocities of grains barely compress, and compressing costs more time than
    // the bytes it saves on a local disk; worth it for slow or remote storage.
    bool zlib = false;
    int zlibLevel = 1;  // the fastest level: most of the gain on grain data comes at level 1
};

void writeFrameVtu(const OutputFrame& frame, const VtuOptions& options, AtomicFile& out);

}  // namespace deme
