// A GoogleTest fixture with a per-test scratch directory, removed afterwards.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

namespace deme_test {

class ScratchDirTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = std::filesystem::temp_directory_path() /
              ("deme_" + std::string(info->test_suite_name()) + "_" +
               std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "_" + info->name());
        std::filesystem::create_directories(dir);
    }
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
    // Writes `text` to dir/name as is (binary, so CRLF tests keep their '\r'); returns the path.
    std::string write(const std::string& name, const std::string& text) {
        const std::string p = (dir / name).string();
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }
    std::filesystem::path dir;
};

}  // namespace deme_test
