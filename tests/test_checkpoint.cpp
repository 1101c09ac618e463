// Checkpoint and restart (docs/checkpoint.md). A run of N steps, a checkpoint, a new solver built by
// the same script up to Initialize() that reads it, and N more steps must equal 2N straight steps
// bit for bit on the CPU (its trajectories do not depend on when contacts are detected, see
// Determinism.*, nor on the detection mode, see Async.*), in synchronous and asynchronous mode, in
// this process and in a new one. Tolerance: none. Bad files are errors that say what is wrong and
// leave the solver as it was.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

#include "CheckpointScenes.h"
#include "ForceModelTestUtil.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "io/AtomicFile.h"
#include "io/CheckpointFile.h"
#include "io/CheckpointState.h"

using namespace deme;
using namespace deme_test;

namespace {

const size_t N = 2000;  // steps before and after the checkpoint

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}
void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// The state a checkpoint holds, read with the engine's own section reader.
struct Saved {
    SimState state;
    double time = 0.0;
    uint64_t step = 0;
};
Saved savedState(const std::string& path, size_t ownerWildcards, size_t geometryWildcards) {
    const CheckpointSections secs = readCheckpointFile(path, "test");
    Saved out;
    out.state.wildcards.owner.resize(ownerWildcards);
    out.state.wildcards.geometry.resize(geometryWildcards);
    for (const auto& [name, bytes] : secs.list) {
        ByteReader in(bytes.data(), bytes.size(), "test", path);
        if (name == "state") readStateSection(in, out.state, "test", path);
        if (name == "clock") {
            out.time = in.value<double>("time");
            out.step = in.value<uint64_t>("step");
        }
    }
    return out;
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Contacts with a history or a persistence mark, by key: what the contact set hands on. (Pairs in
// the set without either are apart; which of them are in the set depends on when detection ran.)
std::map<uint64_t, std::vector<float>> histories(const SimState& s) {
    std::map<uint64_t, std::vector<float>> out;
    const size_t W = s.numWildcards;
    for (size_t c = 0; c < s.contacts.size(); c++) {
        std::vector<float> w(s.contacts.wildcards.begin() + (ptrdiff_t)(c * W),
                             s.contacts.wildcards.begin() + (ptrdiff_t)((c + 1) * W));
        bool any = s.contacts.persistent[c] != 0;
        for (float v : w) any = any || v != 0.f;
        w.push_back((float)s.contacts.persistent[c]);
        if (any) out[contactKey(s.contacts.geomA[c], s.contacts.geomB[c])] = w;
    }
    return out;
}

// Bit for bit: every owner field (poses, velocities, travel, last contact forces, families), the
// owner and geometry wildcards, the contact histories, the clock.
void expectSameRun(const Saved& a, const Saved& b) {
    EXPECT_EQ(a.time, b.time);
    EXPECT_EQ(a.step, b.step);
    forEachOwnerField(a.state.owners, b.state.owners, [](const auto& x, const auto& y, FieldRole) {
        EXPECT_TRUE(sameBits(x, y));
    });
    ASSERT_EQ(a.state.wildcards.owner.size(), b.state.wildcards.owner.size());
    for (size_t i = 0; i < a.state.wildcards.owner.size(); i++)
        EXPECT_TRUE(sameBits(a.state.wildcards.owner[i], b.state.wildcards.owner[i]));
    for (size_t i = 0; i < a.state.wildcards.geometry.size(); i++)
        EXPECT_TRUE(sameBits(a.state.wildcards.geometry[i], b.state.wildcards.geometry[i]));
    const auto ha = histories(a.state), hb = histories(b.state);
    EXPECT_GT(ha.size(), 20u);  // grains are in contact: histories are there to be carried
    EXPECT_TRUE(ha == hb) << ha.size() << " vs " << hb.size() << " contacts with history";
}

size_t ownerWildcardsOf(const CheckpointScene& sc) { return sc.customModel ? 1 : 0; }

std::string modelBody(const CheckpointScene& sc) { return sc.customModel ? hertzMindlinSnippet() : ""; }

// The straight run and the restarted one, both ending in a checkpoint that is compared.
void expectRestartIsExact(const CheckpointScene& sc, const std::filesystem::path& dir) {
    const std::string ref = (dir / "straight.ckpt").string(), mid = (dir / "mid.ckpt").string(),
                      end = (dir / "restarted.ckpt").string(), writerEnd = (dir / "writer.ckpt").string();
    {
        DEMSolver sim;
        buildCheckpointScene(sim, sc, modelBody(sc));
        checkpointScenePhase1(sim, sc, N);
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(ref);
    }
    {
        DEMSolver sim;
        buildCheckpointScene(sim, sc, modelBody(sc));
        checkpointScenePhase1(sim, sc, N);
        sim.WriteCheckpoint(mid);
        // Writing a checkpoint does not change the run that wrote it.
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(writerEnd);
    }
    {
        DEMSolver sim;  // the new process's solver
        buildCheckpointScene(sim, sc, modelBody(sc));
        sim.ReadCheckpoint(mid);
        EXPECT_EQ(sim.GetTimeStep(), 1.5e-5);  // as UpdateStepSize left it
        EXPECT_EQ(sim.GetGravitationalAcceleration().x, 0.5f);
        if (sc.customModel) {
            EXPECT_EQ(sim.GetOwnerWildcardValue("Q", 3), 0.53f);
            EXPECT_EQ(sim.GetSphereWildcardValue("g", 5), 0.3f);
            EXPECT_GT(sim.GetNumPersistentContacts(), 0u);
        }
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(end);
    }
    const size_t W = ownerWildcardsOf(sc), G = sc.customModel ? 1 : 0;
    const Saved straight = savedState(ref, W, G);
    SCOPED_TRACE("restarted run");
    expectSameRun(straight, savedState(end, W, G));
    SCOPED_TRACE("the run that wrote the checkpoint");
    expectSameRun(straight, savedState(writerEnd, W, G));
}

class Checkpoint : public ScratchDirTest {};

}  // namespace

TEST_F(Checkpoint, RestartIsBitForBitSynchronous) {
    CheckpointScene sc;
    sc.async = false;
    expectRestartIsExact(sc, dir);
}

// Asynchronous detection, a container with a prescribed motion of t (the clock must be restored).
TEST_F(Checkpoint, RestartIsBitForBitAsynchronous) {
    CheckpointScene sc;
    sc.async = true;
    sc.shaken = true;
    expectRestartIsExact(sc, dir);
}

// Contact, owner and geometry wildcards of a custom model, and persistent contacts.
TEST_F(Checkpoint, RestartCarriesAllWildcardsAndPersistentContacts) {
    CheckpointScene sc;
    sc.customModel = true;
    expectRestartIsExact(sc, dir);
}
