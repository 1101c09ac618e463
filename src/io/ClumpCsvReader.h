// Reader for clump template CSV files (component spheres of one clump), as shipped with DEM-Engine.
#pragma once

#include <string>
#include <vector>

#include <deme/VectorTypes.h>

namespace deme {

struct ClumpSpheres {
    std::vector<float3> positions;  // sphere centres in the clump's own frame
    std::vector<float> radii;
};

// Format: a header row naming columns x,y,z,r (any order, case-insensitive, surrounding spaces ignored;
// extra columns are allowed and ignored), then one sphere per row with as many fields as the header.
// Blank lines and lines whose first non-blank character is '#' are skipped anywhere, also before the
// header. Windows line endings and a UTF-8 byte-order mark are tolerated.
// Every error throws deme::Error via throwFileError(call, path, line, ...): unreadable file (line 0),
// no header row (line = number of lines in the file), a header lacking or repeating one of x,y,z,r,
// wrong field count, non-numeric or non-finite field (names the column), radius <= 0 (at the offending
// line), and no sphere rows (at the header line).
ClumpSpheres readClumpCsv(const std::string& path, const std::string& call);

}  // namespace deme
