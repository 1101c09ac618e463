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
void readStateSection(ByteReader& in, SimState& s, const std::string& call, const std::string& path);

}  // namespace deme
