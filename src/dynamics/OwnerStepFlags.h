// The bits a step leaves per owner in IntegrationScratch::flags (state/StateFields.h): written by
// the owner's step (dynamics/OwnerStep.h), read by the sweeps after it and by the next force pass
// (dynamics/ContactStep.h: a parked clump touches nothing).
#pragma once

#include <deme/HostDevice.h>  // the fixed-width integers, also under NVRTC

namespace deme {

enum OwnerStepFlag : uint8_t {
    STEP_NOT_FINITE = 1,
    STEP_TOO_FAST = 2,
    STEP_LEFT_DOMAIN = 4,
    STEP_LARGE_ROTATION = 8,  // orientation still to be advanced by the exact (scalar) step
    STEP_MOVED = 16,          // its geometry may have moved: cached vertices need refreshing
    STEP_PARKED = 32,         // a clump that left under the "remove" exit policy, parked (parkingPosition)
};
constexpr uint8_t STEP_FAULTS = STEP_NOT_FINITE | STEP_TOO_FAST | STEP_LEFT_DOMAIN;

}  // namespace deme
