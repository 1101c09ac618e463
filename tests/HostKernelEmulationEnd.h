// Ends the kernel include that HostKernelEmulation.h began.
#undef __global__
#undef __device__
#undef __launch_bounds__
