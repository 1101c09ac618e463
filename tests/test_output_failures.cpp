// Failed writes: a file is written to a temporary name and renamed, so a write that fails midway
// (an I/O error, a removed folder) or a writer killed midway leaves the previous file of that name
// as it was and no half-written file under the real name; a failure in the writer thread surfaces
// as a deme::Error at the next output call or FlushOutput.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "PythonCheck.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "io/AtomicFile.h"

using namespace deme;
using namespace deme_test;
namespace fs = std::filesystem;

extern char** environ;

namespace {

class OutputFailure : public ScratchDirTest {
  protected:
    void TearDown() override {
        failAtomicFilesAfterBytes(0);
        ScratchDirTest::TearDown();
    }
};

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<fs::path> temporaryFiles(const fs::path& dir) {
    std::vector<fs::path> t;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".tmp") t.push_back(e.path());
    return t;
}

struct Grains {
    DEMSolver sim;
    Grains() {
        sim.SetVerbosity("QUIET");
        sim.SetOutputContent("ABSV VEL");
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.5));
        sim.InstructBoxDomainDimension(1, 1, 1);
        auto pts = HCPSampler(0.021f).SampleBox(make_float3(0, 0, 0), make_float3(0.1f, 0.1f, 0.1f));
        sim.AddClumps(sim.LoadSphereType(1e-3f, 0.01f, mat), pts);
        sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
        sim.SetInitTimeStep(1e-4);
        sim.Initialize();
    }
};

}  // namespace

// An I/O error midway through the second write of a file: the first file stays, byte for byte.
TEST_F(OutputFailure, FailedWriteLeavesThePreviousFileAndRaisesAtTheNextCall) {
    Grains g;
    const fs::path vtu = dir / "spheres.vtu", csv = dir / "spheres.csv";
    for (const char* format : {"VTU", "CSV"}) {
        const fs::path target = std::string(format) == "VTU" ? vtu : csv;
        g.sim.SetOutputFormat(format);
        g.sim.WriteSphereFile(target.string());
        g.sim.FlushOutput();
        const std::string before = readBytes(target);
        ASSERT_GT(before.size(), 2000u);

        g.sim.DoDynamics(0.01);
        failAtomicFilesAfterBytes(1000);
        g.sim.WriteSphereFile(target.string());  // returns at once: the write fails in the background
        const std::string msg = demeErrorMessage([&] { g.sim.FlushOutput(); });
        failAtomicFilesAfterBytes(0);
        EXPECT_EQ(msg.rfind("WriteSphereFile:", 0), 0u) << msg;
        EXPECT_NE(msg.find(target.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("reported by FlushOutput"), std::string::npos) << msg;
        EXPECT_EQ(readBytes(target), before) << format;
        EXPECT_TRUE(temporaryFiles(dir).empty());

        // Reported by the next output call instead, which then writes nothing itself.
        failAtomicFilesAfterBytes(1000);
        g.sim.WriteSphereFile(target.string());
        const std::string msg2 = demeErrorMessage([&] { g.sim.WriteClumpFile((dir / "clumps.csv").string()); });
        failAtomicFilesAfterBytes(0);
        EXPECT_NE(msg2.find("reported by WriteClumpFile"), std::string::npos) << msg2;
        EXPECT_FALSE(fs::exists(dir / "clumps.csv"));
        EXPECT_EQ(readBytes(target), before);
        // Once reported, the error is gone and writing works again.
        g.sim.WriteSphereFile(target.string());
        g.sim.FlushOutput();
        EXPECT_NE(readBytes(target), before);
    }
}

TEST_F(OutputFailure, RemovedFolderIsAnErrorNamingThePath) {
    Grains g;
    const fs::path gone = dir / "gone";
    fs::create_directories(gone);
    fs::remove(gone);
    for (const char* format : {"VTU", "CSV"}) {
        g.sim.SetOutputFormat(format);
        const std::string path = (gone / "frame").string();
        g.sim.WriteSphereFile(path);
        const std::string msg = demeErrorMessage([&] { g.sim.FlushOutput(); });
        EXPECT_EQ(msg.rfind("WriteSphereFile:", 0), 0u) << msg;
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
    }
    g.sim.WriteSnapshot((gone / "a.png").string());
    EXPECT_NE(demeErrorMessage([&] { g.sim.FlushOutput(); }).find("WriteSnapshot:"), std::string::npos);
    EXPECT_FALSE(fs::exists(gone));
}

// A writer process killed (SIGKILL) while it rewrites a frame: the file under the real name is
// always a whole frame, the last one written or the one before, never a part of one. Repeated until
// the kill lands inside a write (a temporary file is left behind, the evidence of it).
TEST_F(OutputFailure, KilledWriterLeavesAWholeFrame) {
    const fs::path target = dir / "frame.vtu";
    const int spheres = 200000;
    bool hitMidWrite = false;
    for (int attempt = 0; attempt < 6 && !hitMidWrite; attempt++) {
        int out[2];
        ASSERT_EQ(pipe(out), 0);
        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_adddup2(&fa, out[1], STDOUT_FILENO);
        posix_spawn_file_actions_addclose(&fa, out[0]);
        const std::string n = std::to_string(spheres), path = target.string();
        char* argv[] = {(char*)DEME_FRAME_WRITER, (char*)path.c_str(), (char*)n.c_str(), nullptr};
        pid_t pid;
        ASSERT_EQ(posix_spawn(&pid, DEME_FRAME_WRITER, &fa, nullptr, argv, environ), 0);
        posix_spawn_file_actions_destroy(&fa);
        close(out[1]);
        FILE* lines = fdopen(out[0], "r");
        std::string times;
        char buf[128];
        int written = 0;
        // Every frame announced may be the one in place (a kill between its rename and its
        // "written" line), but nothing else.
        auto readLine = [&]() {
            if (!std::fgets(buf, sizeof buf, lines)) return false;
            int k;
            char t[64];
            if (std::sscanf(buf, "writing %d %63s", &k, t) == 2) times += std::string(" ") + t;
            if (std::sscanf(buf, "written %d %63s", &k, t) == 2) written++;
            return true;
        };
        while (written < 2 + attempt % 2 && readLine()) {
        }
        ASSERT_GE(written, 2) << "the writer stopped early";
        // Into the next frame's write: a few to a few tens of milliseconds in.
        std::this_thread::sleep_for(std::chrono::milliseconds(5 + 12 * attempt));
        kill(pid, SIGKILL);
        int status;
        waitpid(pid, &status, 0);
        while (readLine()) {
        }
        std::fclose(lines);
        ASSERT_TRUE(WIFSIGNALED(status));
        const std::vector<fs::path> tmp = temporaryFiles(dir);
        hitMidWrite = !tmp.empty();
        const ScriptResult r = runPythonCheck("check_vtu.py", "complete " + path + " " + n + times);
        EXPECT_EQ(r.status, 0) << r.output;
        for (const fs::path& p : tmp) fs::remove(p);  // what a crash leaves: hidden, named *.tmp
    }
    EXPECT_TRUE(hitMidWrite) << "no kill landed inside a write in 6 attempts";
}
