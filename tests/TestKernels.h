// Kernel sources that only tests compile (tests/kernels/), read from the source tree.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace deme_test {

// The text of tests/kernels/<name>; fails the test if it cannot be read.
inline std::string testKernelText(const std::string& name) {
    std::ifstream in(std::string(DEME_TEST_SOURCE_DIR) + "/kernels/" + name);
    if (!in) ADD_FAILURE() << "cannot read tests/kernels/" << name;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The name the kernel is compiled under (compiler messages and cache keys).
constexpr const char* kExampleKernelPath = "tests/kernels/Example.cu";

}  // namespace deme_test
