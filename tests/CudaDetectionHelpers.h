// What the GPU detection tests share (tests/test_cuda_dormant_detection.cpp,
// tests/test_cuda_detection_slabs.cpp): their scenes, grid and rules, and a synchronous detection by
// CudaKinematics with its contact list brought to the host. Only with the CUDA backend built
// (DEME_TESTS_CUDA_BUILT).
#pragma once

#include "DetectionScenes.h"
#include "backend/cpu/ContactDetector.h"
#include "backend/cuda/CudaKinematics.h"
#include "backend/cuda/Device.h"
#include "kinematics/BinGridSizing.h"
#include "runtime/FamilyRules.h"
#include "runtime/Settings.h"

namespace deme_test {

// kin's detection of its state with margin `margin`, the outbox's pairs downloaded.
inline deme::DetectedContacts detectOnGpu(deme::cuda::CudaKinematics& kin, double margin) {
    deme::DetectionOrder order;
    order.margin = margin;
    deme::DetectionReport report;
    kin.detectNow(order, report);
    const size_t n = report.numPairs;
    deme::DetectedContacts gpu;
    gpu.geomA.resize(n);
    gpu.geomB.resize(n);
    if (n) {
        kin.outbox().geomA.downloadAsync(gpu.geomA.data(), n, nullptr);
        kin.outbox().geomB.downloadAsync(gpu.geomB.data(), n, nullptr);
    }
    deme::cuda::synchronize(nullptr);
    return gpu;
}

}  // namespace deme_test
