// NVRTC loaded when the CUDA backend first compiles a kernel, not when the program starts. Linked,
// its library (110 MB) took 28 MB of resident memory in every process of a CUDA build, runs on the
// CPU backend included: 10 bytes a sphere of a 2.9 M-sphere CPU run (docs/memory.md).
#pragma once

#include <nvrtc.h>

#include <string>

namespace deme::cuda {

// The NVRTC functions the backend calls.
struct NvrtcApi {
    decltype(&nvrtcGetErrorString) getErrorString;
    decltype(&nvrtcVersion) version;
    decltype(&nvrtcGetNumSupportedArchs) getNumSupportedArchs;
    decltype(&nvrtcGetSupportedArchs) getSupportedArchs;
    decltype(&nvrtcCreateProgram) createProgram;
    decltype(&nvrtcDestroyProgram) destroyProgram;
    decltype(&nvrtcCompileProgram) compileProgram;
    decltype(&nvrtcGetProgramLogSize) getProgramLogSize;
    decltype(&nvrtcGetProgramLog) getProgramLog;
    decltype(&nvrtcGetPTXSize) getPTXSize;
    decltype(&nvrtcGetPTX) getPTX;
    decltype(&nvrtcGetCUBINSize) getCUBINSize;
    decltype(&nvrtcGetCUBIN) getCUBIN;
};

// The library's functions, loaded by the first call in the process (from the toolkit the engine was
// built with, else by its name on the loader's path); a deme::Error naming `call` where it cannot be
// loaded or lacks a function.
const NvrtcApi& nvrtc(const std::string& call);

// (nvrtcIsLoaded: backend/cuda/NvrtcCompiler.h.)

}  // namespace deme::cuda
