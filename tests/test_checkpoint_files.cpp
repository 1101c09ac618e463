// Checkpoint files (docs/checkpoint.md): a truncated, corrupted, wrong-version or other-scene file,
// a file that is no checkpoint and a missing one are errors that say which and leave the solver as
// it was; a batch waiting for UpdateClumps makes both calls errors; what is read is written back
// byte for byte; a write that fails midway keeps the previous checkpoint. (Restarts:
// test_checkpoint.cpp.)
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "CheckpointScenes.h"
#include "ForceModelTestUtil.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "io/AtomicFile.h"
#include "io/CheckpointFile.h"
#include "runtime/SceneFingerprint.h"

#include <zlib.h>

using namespace deme;
using namespace deme_test;

namespace {

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}
void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

class CheckpointFiles : public ScratchDirTest {};

}  // namespace

namespace {

// A solver of the standard scene and a good checkpoint of it, for the tests of bad files.
struct BadFileSetup {
    CheckpointScene sc;
    std::string good, before, after;
    DEMSolver sim;
    explicit BadFileSetup(const std::filesystem::path& dir)
        : good((dir / "good.ckpt").string()), before((dir / "before.ckpt").string()), after((dir / "after.ckpt").string()) {
        {
            DEMSolver writer;
            buildCheckpointScene(writer, sc);
            checkpointScenePhase1(writer, sc, 200);
            writer.WriteCheckpoint(good);
        }
        pile = buildCheckpointScene(sim, sc);
        for (int k = 0; k < 50; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(before);
    }
    std::shared_ptr<DEMClumpBatch> pile;
    // The error that reading `path` gives; the solver must be as it was (the same checkpoint bytes).
    std::string errorReading(const std::string& path) {
        const std::string msg = demeErrorMessage([&] { sim.ReadCheckpoint(path); });
        sim.WriteCheckpoint(after);
        EXPECT_TRUE(bytesOf(after) == bytesOf(before)) << "the solver changed";
        EXPECT_NE(msg.find("ReadCheckpoint"), std::string::npos) << msg;
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        return msg;
    }
};

bool has(const std::string& msg, const std::string& what) { return msg.find(what) != std::string::npos; }

// The header's version field (bytes 8..11) set to `version`, with the header checksum made right
// again, so that only the version is wrong.
std::string withVersion(std::string bytes, uint32_t version) {
    std::memcpy(&bytes[8], &version, 4);
    const uint32_t crc = (uint32_t)crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), 28);
    std::memcpy(&bytes[28], &crc, 4);
    return bytes;
}

}  // namespace

TEST_F(CheckpointFiles, TruncatedFileIsAnErrorAndChangesNothing) {
    BadFileSetup t(dir);
    const std::string bytes = bytesOf(t.good), p = (dir / "bad.ckpt").string();
    writeBytes(p, bytes.substr(0, bytes.size() - 1000));
    const std::string msg = t.errorReading(p);
    EXPECT_TRUE(has(msg, "truncated")) << msg;
    writeBytes(p, bytes.substr(0, 20));
    EXPECT_TRUE(has(t.errorReading(p), "truncated"));
    writeBytes(p, "");
    EXPECT_TRUE(has(t.errorReading(p), "truncated"));
}

TEST_F(CheckpointFiles, CorruptedFileIsAChecksumErrorAndChangesNothing) {
    BadFileSetup t(dir);
    std::string bytes = bytesOf(t.good);
    const std::string p = (dir / "bad.ckpt").string();
    bytes[bytes.size() / 2] ^= 0x10;  // one bit, in the middle of the state
    writeBytes(p, bytes);
    const std::string msg = t.errorReading(p);
    EXPECT_TRUE(has(msg, "corrupted") && has(msg, "checksum")) << msg;
    std::string header = bytesOf(t.good);
    header[20] ^= 0x01;  // the payload length
    writeBytes(p, header);
    EXPECT_TRUE(has(t.errorReading(p), "checksum"));
}

TEST_F(CheckpointFiles, WrongVersionIsAnErrorAndChangesNothing) {
    BadFileSetup t(dir);
    const std::string p = (dir / "bad.ckpt").string();
    writeBytes(p, withVersion(bytesOf(t.good), 99));
    const std::string msg = t.errorReading(p);
    EXPECT_TRUE(has(msg, "version 99") &&
                has(msg, "reads versions " + std::to_string(OLDEST_CHECKPOINT_FORMAT_VERSION) + " to " +
                             std::to_string(CHECKPOINT_FORMAT_VERSION)))
        << msg;
}

TEST_F(CheckpointFiles, OtherSceneIsAnErrorAndChangesNothing) {
    BadFileSetup t(dir);
    const std::string p = (dir / "other.ckpt").string();
    auto writeOther = [&](const CheckpointScene& sc) {
        DEMSolver other;
        buildCheckpointScene(other, sc, sc.customModel ? hertzMindlinSnippet() : "");
        other.DoStepDynamics();
        other.WriteCheckpoint(p);
    };
    CheckpointScene model = t.sc;
    model.customModel = true;  // five contact wildcards instead of four
    writeOther(model);
    std::string msg = t.errorReading(p);
    EXPECT_TRUE(has(msg, "another scene") && has(msg, "5 contact wildcards in the checkpoint's scene, 4 in this one"))
        << msg;
    CheckpointScene friction = t.sc;
    friction.mu = 0.6;  // the same counts, other material properties
    writeOther(friction);
    msg = t.errorReading(p);
    EXPECT_TRUE(has(msg, "another scene") && has(msg, "material properties differ")) << msg;
}

// Which pairs a custom model is called for is part of the model a checkpoint was written with; the
// default (every pair) adds nothing to the hash, so checkpoints from before the setting still read.
TEST(SceneFingerprintModel, CustomModelNotCalledForApartPairsIsAnotherModel) {
    SimState s;
    ModelLayout custom;
    custom.kind = DEMForceModel::Kind::CUSTOM;
    custom.source = "force += B2A;";
    ModelLayout contactsOnly = custom;
    contactsOnly.calledForApartPairs = false;
    EXPECT_NE(sceneFingerprint(s, custom).model, sceneFingerprint(s, contactsOnly).model);
    EXPECT_NE(fingerprintMismatch(sceneFingerprint(s, contactsOnly), sceneFingerprint(s, custom)).find("force model"),
              std::string::npos);
    ModelLayout builtIn, builtInFlagged;  // the built-in models' setting is fixed: no part of the hash
    builtInFlagged.calledForApartPairs = false;
    EXPECT_EQ(sceneFingerprint(s, builtIn).model, sceneFingerprint(s, builtInFlagged).model);
}

// FNV-1a over a run of zero bytes, one multiplication by a power of the prime, is the byte loop's
// hash (the layout without sphere offsets hashes them so; across layouts:
// SceneAssembly.OneSphereClumpsAreTheirOwnersFromTheStart).
TEST(SceneFingerprintHash, ZeroRunsHashAsTheirBytes) {
    std::mt19937_64 rng(5);
    for (uint64_t count : {0ull, 1ull, 2ull, 3ull, 12ull, 255ull, 4096ull, 123457ull}) {
        const uint64_t start = rng();
        uint64_t h = start;
        for (uint64_t i = 0; i < count; i++) {
            h ^= 0u;                // the byte
            h *= 1099511628211ull;  // FNV's 64-bit prime
        }
        EXPECT_EQ(fnv1aAfterZeroBytes(start, count), h) << count << " zero bytes";
    }
}

TEST_F(CheckpointFiles, OtherFilesAreErrors) {
    BadFileSetup t(dir);
    EXPECT_TRUE(has(t.errorReading(write("notes.txt", "not a checkpoint at all")), "not a checkpoint"));
    EXPECT_TRUE(has(t.errorReading((dir / "missing.ckpt").string()), "cannot open"));
    DEMSolver fresh;
    EXPECT_TRUE(has(demeErrorMessage([&] { fresh.ReadCheckpoint(t.good); }), "after Initialize"));
    EXPECT_TRUE(has(demeErrorMessage([&] { fresh.WriteCheckpoint(t.good); }), "after Initialize"));
    // After all that, the good file still continues the run.
    t.sim.ReadCheckpoint(t.good);
    t.sim.DoStepDynamics();
}

// Clumps that AddClumps added and that wait for UpdateClumps are not in the state: writing would
// lose them and reading would replace the state their ids follow. Both are errors until then.
TEST_F(CheckpointFiles, ClumpsWaitingForUpdateClumpsAreAnError) {
    BadFileSetup t(dir);
    t.sim.AddClumps(t.pile->GetTypes()[0], {make_float3(0, 0, 0.02f)});
    const std::string onWrite = demeErrorMessage([&] { t.sim.WriteCheckpoint((dir / "w.ckpt").string()); });
    EXPECT_TRUE(has(onWrite, "WriteCheckpoint") && has(onWrite, "UpdateClumps")) << onWrite;
    EXPECT_FALSE(std::filesystem::exists(dir / "w.ckpt"));
    const std::string onRead = demeErrorMessage([&] { t.sim.ReadCheckpoint(t.good); });
    EXPECT_TRUE(has(onRead, "ReadCheckpoint") && has(onRead, "UpdateClumps")) << onRead;
    t.sim.UpdateClumps();
    t.sim.WriteCheckpoint((dir / "w.ckpt").string());
    EXPECT_TRUE(std::filesystem::exists(dir / "w.ckpt"));
}

// What was read is what is written back, byte for byte, before any step (the restored contact
// set, schedule and travel included).
TEST_F(CheckpointFiles, ReadThenWriteGivesTheSameFile) {
    BadFileSetup t(dir);
    t.sim.ReadCheckpoint(t.good);
    const std::string again = (dir / "again.ckpt").string();
    t.sim.WriteCheckpoint(again);
    EXPECT_TRUE(bytesOf(again) == bytesOf(t.good));
}

// A write that fails midway (a full disk, a crash) leaves the previous checkpoint as it was.
TEST_F(CheckpointFiles, FailedWriteKeepsThePreviousCheckpoint) {
    BadFileSetup t(dir);
    const std::string p = (dir / "run.ckpt").string();
    t.sim.WriteCheckpoint(p);
    const std::string previous = bytesOf(p);
    for (int k = 0; k < 20; k++) t.sim.DoStepDynamics();
    failAtomicFilesAfterBytes(4096);
    const std::string msg = demeErrorMessage([&] { t.sim.WriteCheckpoint(p); });
    failAtomicFilesAfterBytes(0);
    EXPECT_TRUE(has(msg, "WriteCheckpoint") && has(msg, "unchanged")) << msg;
    EXPECT_TRUE(bytesOf(p) == previous);
    size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.path().filename().string()[0] == '.';
    EXPECT_EQ(files, 0u) << "a temporary file was left behind";
    t.sim.ReadCheckpoint(p);  // and it still reads
}
