// The "state" section of a checkpoint (io/Checkpoint.h): a SimState's arrays as named records,
// made from the field lists of state/StateFields.h, plus the host tables beside them.
#pragma once

#include <string>

#include "io/CheckpointFile.h"
#include "state/SimState.h"

namespace deme {

void writeStateSection(const SimState& s, ByteWriter& out);

// Fills `s` (a copy of the reader's own state, so that everything the section does not hold keeps
// a valid size) from the section; throws deme::Error naming `call` and `path` if a field is missing,
// unknown to this build, of another element size, or of a length that does not fit the others.
// `version` is the file's format (io/CheckpointFile.h): a version-1 file's owners' travel (since the
// start, doubles) goes to `travelSinceStart`, the state's travel left zero.
void readStateSection(ByteReader& in, SimState& s, const std::string& call, const std::string& path, uint32_t version,
                      std::vector<double>& travelSinceStart);
// A section of this build's version.
inline void readStateSection(ByteReader& in, SimState& s, const std::string& call, const std::string& path) {
    std::vector<double> none;
    readStateSection(in, s, call, path, CHECKPOINT_FORMAT_VERSION, none);
}

}  // namespace deme
