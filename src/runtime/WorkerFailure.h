// A worker thread (kT on the CPU or the GPU) stores what it threw; the thread that drives it rethrows
// it once, as a deme::Error that names the user's call and the worker.
#pragma once

#include <exception>
#include <string>

#include <deme/Error.h>

namespace deme {

inline void rethrowWorkerFailure(std::exception_ptr& failure, const std::string& call, const std::string& worker) {
    if (!failure) return;
    std::exception_ptr f = failure;
    failure = nullptr;
    try {
        std::rethrow_exception(f);
    } catch (const std::exception& e) {
        throwError(call, worker + " failed: " + e.what());
    }
}

}  // namespace deme
