// A per-test scratch directory, removed afterwards: ScratchDir on its own (the backend fixture holds
// one), or ScratchDirTest as a GoogleTest fixture.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

namespace deme_test {

class ScratchDir {
  public:
    // Named after the running test; '/' (in the names of parameterised tests) becomes '_', and the
    // clock keeps two instances of one test apart when they run at the same time.
    ScratchDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string(info->test_suite_name()) + "_" +
                           std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "_" +
                           info->name();
        for (char& c : name)
            if (c == '/') c = '_';
        m_path = std::filesystem::temp_directory_path() / ("deme_" + name);
        std::filesystem::create_directories(m_path);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }
    // Writes `text` to path()/name as is (binary, so CRLF tests keep their '\r'); returns the path.
    std::string write(const std::string& name, const std::string& text) const {
        const std::string p = (m_path / name).string();
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }

  private:
    std::filesystem::path m_path;
};

class ScratchDirTest : public ::testing::Test {
  protected:
    void SetUp() override {
        m_scratch.reset(new ScratchDir());
        dir = m_scratch->path();
    }
    void TearDown() override { m_scratch.reset(); }
    std::string write(const std::string& name, const std::string& text) { return m_scratch->write(name, text); }
    std::filesystem::path dir;

  private:
    std::unique_ptr<ScratchDir> m_scratch;
};

}  // namespace deme_test
