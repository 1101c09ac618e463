// Programmatic dependent launch (GPUs of compute capability 9.0 and newer): a step's kernels are
// queued so that the next one's blocks may be scheduled while the one before is still draining
// (LaunchList::overlapLaunches, backend/cuda/LaunchList.h). At lab scale a step is a chain of
// short kernels, and the gap between two of them is a good part of the step.
//
// Every kernel of such a chain calls beginDependentKernel() first, in every thread and before it
// reads anything the kernels before may have written: griddepcontrol.wait returns once the kernel
// before it has finished and its writes are visible. (What no kernel that can be running then
// writes may be read before: the owner step's inputs and the batch's stop flag after a force pass,
// a contact's ids in the force pass; kernels/Dynamics.cu and ForcePassKernel.cuh say why.) A block that returned before
// waiting could let its kernel finish before the one before it, and the kernel after both would then see neither's
// writes in order; so the wait comes before any early return. Then it lets the next kernel be scheduled: that kernel
// waits in turn, so at most one kernel is ever ahead, spinning at its own wait. On older GPUs, and for kernels launched
// the ordinary way, both instructions are no-ops.
#pragma once

namespace deme {

__device__ inline void beginDependentKernel() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
    asm volatile("griddepcontrol.wait;" ::: "memory");
    asm volatile("griddepcontrol.launch_dependents;" ::: "memory");
#endif
}

}  // namespace deme
