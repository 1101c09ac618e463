// Checkpoint and restart (docs/checkpoint.md). A run of N steps, a checkpoint, a new solver built by
// the same script up to Initialize() that reads it, and N more steps must equal 2N straight steps
// bit for bit on the CPU (its trajectories do not depend on when contacts are detected, see
// Determinism.*, nor on the detection mode, see Async.*), in synchronous and asynchronous mode, in
// this process and in a new one. Tolerance: none. (Bad files: test_checkpoint_files.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

#include "CheckpointScenes.h"
#include "ForceModelTestUtil.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "io/CheckpointFile.h"
#include "io/CheckpointState.h"
#include "state/OwnerCentre.h"

using namespace deme;
using namespace deme_test;

namespace {

const size_t N = 2000;  // steps before and after the checkpoint


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

// Bit for bit: every owner field (poses, velocities, last contact forces, families), the owner and
// geometry wildcards, the contact histories, the clock; and where both runs detected on the same
// steps, their travel since the set's snapshot.
void expectSameRun(const Saved& a, const Saved& b, bool sameContactSet = false) {
    EXPECT_EQ(a.time, b.time);
    EXPECT_EQ(a.step, b.step);
    forEachOwnerField(a.state.owners, b.state.owners, [&](const auto& x, const auto& y, FieldRole) {
        const bool travel = static_cast<const void*>(&x) == static_cast<const void*>(&a.state.owners.travel);
        if (!travel || sameContactSet) EXPECT_TRUE(sameBits(x, y));
    });
    ASSERT_EQ(a.state.wildcards.owner.size(), b.state.wildcards.owner.size());
    for (size_t i = 0; i < a.state.wildcards.owner.size(); i++)
        EXPECT_TRUE(sameBits(a.state.wildcards.owner[i], b.state.wildcards.owner[i]));
    for (size_t i = 0; i < a.state.wildcards.geometry.size(); i++)
        EXPECT_TRUE(sameBits(a.state.wildcards.geometry[i], b.state.wildcards.geometry[i]));
    const auto ha = histories(a.state), hb = histories(b.state);
    EXPECT_GT(ha.size(), 20u);  // grains are in contact: histories are there to be carried
    EXPECT_TRUE(ha == hb) << ha.size() << " vs " << hb.size() << " contacts with history";
    // With a fixed n_max in synchronous mode, detections fall on the same steps in every run: a
    // restart that goes on with the restored set and schedule ends with the very same set.
    if (sameContactSet) {
        EXPECT_TRUE(sameBits(a.state.contacts.geomA, b.state.contacts.geomA));
        EXPECT_TRUE(sameBits(a.state.contacts.geomB, b.state.contacts.geomB));
    }
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
    const bool fixedSchedule = !sc.async;  // (see CheckpointScenes.h)
    expectSameRun(straight, savedState(end, W, G), fixedSchedule);
    SCOPED_TRACE("the run that wrote the checkpoint");
    expectSameRun(straight, savedState(writerEnd, W, G), fixedSchedule);
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

// Grains added (two batches through UpdateClumps) and removed (RemoveClumpsInFamily, with the
// "remove" exit policy on) before the checkpoint: the restarted run holds the same owners, ids and
// removed totals, and goes on bit for bit.
TEST_F(Checkpoint, RestartAfterInsertionsAndRemovalsIsBitForBit) {
    const CheckpointScene sc;  // synchronous, fixed n_max
    const std::string ref = (dir / "straight.ckpt").string(), mid = (dir / "mid.ckpt").string(),
                      end = (dir / "restarted.ckpt").string();
    auto firstHalf = [&](DEMSolver& sim) {
        auto pile = buildCheckpointScene(sim, sc);
        sim.SetDomainExitPolicy("remove");
        for (size_t k = 0; k < N / 2; k++) sim.DoStepDynamics();
        const auto tmpl = pile->GetTypes()[0];
        auto stays = sim.AddClumps(tmpl, HCPSampler(0.0082f).SampleBox(make_float3(0, 0, -0.012f),
                                                                         make_float3(0.02f, 0.02f, 0.003f)));
        auto goes = sim.AddClumps(tmpl, HCPSampler(0.0082f).SampleBox(make_float3(0, 0, 0.01f),
                                                                        make_float3(0.02f, 0.02f, 0.003f)));
        goes->SetFamily(7);
        sim.UpdateClumps();
        for (size_t k = 0; k < N / 4; k++) sim.DoStepDynamics();
        EXPECT_GT(sim.RemoveClumpsInFamily(7), 10u);
        checkpointScenePhase1(sim, sc, N / 4);
        return stays->GetNumClumps();
    };
    size_t clumps = 0, removed = 0;
    double removedMass = 0.0;
    {
        DEMSolver sim;
        firstHalf(sim);
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(ref);
        clumps = sim.GetNumClumps();
        removed = sim.GetNumRemovedClumps();
        removedMass = sim.GetRemovedMass();
    }
    {
        DEMSolver sim;
        const size_t added = firstHalf(sim);
        EXPECT_GT(added, 10u);
        sim.WriteCheckpoint(mid);
    }
    DEMSolver sim;  // the new process's solver: the scene up to Initialize(), then the checkpoint
    buildCheckpointScene(sim, sc);
    sim.ReadCheckpoint(mid);
    for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
    sim.WriteCheckpoint(end);
    EXPECT_EQ(sim.GetNumClumps(), clumps);
    EXPECT_EQ(sim.GetNumRemovedClumps(), removed);
    EXPECT_GT(removed, 10u);
    EXPECT_EQ(sim.GetRemovedMass(), removedMass);
    expectSameRun(savedState(ref, 0, 0), savedState(end, 0, 0), true);
}

// A family change on a condition (ChangeFamilyWhen) set before the checkpoint goes on after it: it
// acts only after the checkpoint's time (t = 0.04 s; the second half runs to 0.07 s), so the grains
// it freezes in the restarted run are frozen by the restored condition, as in the straight run.
TEST_F(Checkpoint, RestartCarriesFamilyChangeConditions) {
    const CheckpointScene sc;  // synchronous, fixed n_max: conditions are checked at detections
    const std::string ref = (dir / "straight.ckpt").string(), mid = (dir / "mid.ckpt").string(),
                      end = (dir / "restarted.ckpt").string();
    auto firstHalf = [&](DEMSolver& sim) {
        auto pile = buildCheckpointScene(sim, sc);
        sim.SetFamilyFixed(9);
        sim.ChangeFamilyWhen(0, 9, "t > 0.055 && Z < -0.03");
        checkpointScenePhase1(sim, sc, N);
        return sim.Track(pile);
    };
    auto frozen = [](const std::shared_ptr<DEMTracker>& t) {
        size_t n = 0;
        for (unsigned int f : t->GetFamilies()) n += f == 9;
        return n;
    };
    size_t frozenAtCheckpoint = 0, frozenAtEnd = 0;
    {
        DEMSolver sim;
        auto t = firstHalf(sim);
        frozenAtCheckpoint = frozen(t);
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        frozenAtEnd = frozen(t);
        sim.WriteCheckpoint(ref);
    }
    EXPECT_EQ(frozenAtCheckpoint, 0u);
    EXPECT_GT(frozenAtEnd, 20u);
    {
        DEMSolver sim;
        firstHalf(sim);
        sim.WriteCheckpoint(mid);
    }
    DEMSolver sim;  // the new process's script: the scene only, no ChangeFamilyWhen
    auto pile = buildCheckpointScene(sim, sc);
    sim.ReadCheckpoint(mid);
    for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
    sim.WriteCheckpoint(end);
    EXPECT_EQ(frozen(sim.Track(pile)), frozenAtEnd);
    expectSameRun(savedState(ref, 0, 0), savedState(end, 0, 0), true);
}

// A real restart: the first half in one process, the second in another (tools/checkpoint_run.cpp),
// against the straight run in this one.
TEST_F(Checkpoint, RestartInANewProcessIsBitForBit) {
    for (bool async : {false, true}) {
        SCOPED_TRACE(async ? "asynchronous" : "synchronous");
        CheckpointScene sc;
        sc.async = async;
        const std::string mid = (dir / "mid.ckpt").string(), end = (dir / "end.ckpt").string(),
                          ref = (dir / "ref.ckpt").string(), mode = async ? "async" : "sync";
        const std::string tool = std::string("\"") + DEME_CHECKPOINT_RUN + "\" ";
        ASSERT_EQ(std::system((tool + "first \"" + mid + "\" " + std::to_string(N) + " " + mode).c_str()), 0);
        ASSERT_EQ(std::system((tool + "resume \"" + mid + "\" " + std::to_string(N) + " " + mode + " \"" + end + "\"").c_str()), 0);
        DEMSolver sim;
        buildCheckpointScene(sim, sc);
        checkpointScenePhase1(sim, sc, N);
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(ref);
        expectSameRun(savedState(ref, 0, 0), savedState(end, 0, 0), !async);
    }
}

// A state written by an earlier build, which stored each pair's type (`contacts.type`, now derived
// from B: state/ContactTypeOf.h), reads as the same state: the record is spliced into this build's
// section after its record count.
TEST_F(Checkpoint, ReadsAStateThatStillStoresContactTypes) {
    CheckpointScene sc;
    const std::string path = (dir / "mid.ckpt").string();
    {
        DEMSolver sim;
        buildCheckpointScene(sim, sc);
        checkpointScenePhase1(sim, sc, N);
        sim.WriteCheckpoint(path);
    }
    const CheckpointSections secs = readCheckpointFile(path, "test");
    std::string section;
    for (const auto& [name, bytes] : secs.list)
        if (name == "state") section = bytes;
    // The header: clump count, analytical owner count, wildcard count, tracker load flag, removed
    // clump count, removed mass; then the record count.
    const size_t countAt = 8 + 8 + 4 + 1 + 8 + 8;
    ASSERT_GT(section.size(), countAt + 8);
    Saved now;
    {
        ByteReader in(section.data(), section.size(), "test", path);
        readStateSection(in, now.state, "test", path);
    }
    const size_t pairs = now.state.contacts.size();
    ASSERT_GT(pairs, 0u);
    uint64_t records = 0;
    std::memcpy(&records, section.data() + countAt, 8);
    records++;
    std::string old = section;
    std::memcpy(&old[countAt], &records, 8);
    ByteWriter typeRecord;
    typeRecord.text("contacts.type");
    typeRecord.array(std::vector<uint8_t>(pairs, (uint8_t)SPHERE_SPHERE));
    old.insert(countAt + 8, typeRecord.buffer());
    Saved before;
    {
        ByteReader in(old.data(), old.size(), "test", path);
        readStateSection(in, before.state, "test", path);
    }
    EXPECT_EQ(before.state.contacts.geomA, now.state.contacts.geomA);
    EXPECT_EQ(before.state.contacts.geomB, now.state.contacts.geomB);
    EXPECT_TRUE(sameBits(before.state.contacts.wildcards, now.state.contacts.wildcards));
    forEachOwnerField(before.state.owners, now.state.owners,
                      [](const auto& x, const auto& y, FieldRole) { EXPECT_TRUE(sameBits(x, y)); });
    // Any other field this build does not know is still refused.
    ByteWriter unknown;
    unknown.text("contacts.colour");
    unknown.array(std::vector<uint8_t>(pairs, 0));
    std::string other = section;
    std::memcpy(&other[countAt], &records, 8);
    other.insert(countAt + 8, unknown.buffer());
    ByteReader in(other.data(), other.size(), "test", path);
    SimState refused;
    EXPECT_THROW(readStateSection(in, refused, "test", path), deme::Error);
}

// A version-1 file (before the owners' travel counted from the contact set's snapshot) held every
// owner's travel since the start as a double and, in the clock, each one's travel at the set's
// snapshot: made here from this build's file (the travel as K + travel, the snapshot as K, K = 0.5,
// both exact in doubles), it reads as the same state and goes on bit for bit, with the restored
// set; with no snapshot travel (a set that could not go on) it detects afresh, and on the CPU ends
// the same all the same (its trajectories do not depend on when detection runs).
namespace {

// `section` with the record `name` (text, then an array) replaced by `record`.
std::string replaceRecord(const std::string& section, const std::string& name, const std::string& record) {
    ByteWriter key;
    key.text(name);
    const size_t at = section.find(key.buffer());
    EXPECT_NE(at, std::string::npos) << name;
    if (at == std::string::npos) return section;
    const size_t arrayAt = at + key.buffer().size();
    uint32_t elem = 0;
    uint64_t count = 0;
    std::memcpy(&elem, section.data() + arrayAt, 4);
    std::memcpy(&count, section.data() + arrayAt + 4, 8);
    return section.substr(0, at) + record + section.substr(arrayAt + 12 + elem * count);
}

}  // namespace

TEST_F(Checkpoint, ReadsAVersion1FileWithTravelSinceTheStart) {
    CheckpointScene sc;  // synchronous, fixed n_max: a restored set ends in the same set
    const std::string mid = (dir / "mid.ckpt").string();
    {
        DEMSolver sim;
        buildCheckpointScene(sim, sc);
        checkpointScenePhase1(sim, sc, N);
        sim.WriteCheckpoint(mid);
    }
    CheckpointSections secs = readCheckpointFile(mid, "test");
    EXPECT_EQ(secs.version, CHECKPOINT_FORMAT_VERSION);
    Saved now;
    for (const auto& [name, bytes] : secs.list)
        if (name == "state") {
            ByteReader in(bytes.data(), bytes.size(), "test", mid);
            readStateSection(in, now.state, "test", mid);
        }
    const std::vector<float>& travel = now.state.owners.travel;
    ASSERT_FALSE(travel.empty());
    EXPECT_GT(*std::max_element(travel.begin(), travel.end()), 0.f);  // grains moved since the set's snapshot
    const double K = 0.5;
    std::vector<double> sinceStart(travel.size()), atSnapshot(travel.size(), K);
    for (size_t o = 0; o < travel.size(); o++) sinceStart[o] = K + (double)travel[o];
    auto version1 = [&](const std::string& path, bool withSnapshot) {
        CheckpointSections old = secs;
        old.version = 1;
        for (auto& [name, bytes] : old.list) {
            if (name == "state") {
                ByteWriter record;
                record.text("owners.travel");
                record.array(sinceStart);
                bytes = replaceRecord(bytes, "owners.travel", record.buffer());
            }
            if (name == "clock") {  // the resumable flag, the last byte, was the snapshot's travel
                ByteWriter snapshot;
                snapshot.array(withSnapshot ? atSnapshot : std::vector<double>());
                bytes = bytes.substr(0, bytes.size() - 1) + snapshot.buffer();
            }
        }
        writeCheckpointFile(path, old, "test");
    };
    auto runFrom = [&](const std::string& from, const std::string& to) {
        DEMSolver sim;
        buildCheckpointScene(sim, sc);
        sim.ReadCheckpoint(from);
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(to);
        return savedState(to, 0, 0);
    };
    const std::string v1 = (dir / "v1.ckpt").string(), v1Fresh = (dir / "v1-fresh.ckpt").string();
    version1(v1, true);
    version1(v1Fresh, false);
    const Saved ref = runFrom(mid, (dir / "ref.ckpt").string());
    {
        SCOPED_TRACE("version 1, the set restored");
        expectSameRun(ref, runFrom(v1, (dir / "v1-end.ckpt").string()), true);
    }
    {
        SCOPED_TRACE("version 1, detected afresh");
        expectSameRun(ref, runFrom(v1Fresh, (dir / "v1-fresh-end.ckpt").string()));
    }
}

// CPU -> GPU and GPU -> CPU (a GpuParity test: tests/gpu/run.sh runs it; skipped without a GPU). The GPU sums contact forces
// in another order, so its trajectories are not the CPU's bit for bit; measured here: how far a GPU
// run of 2N steps ends from the CPU's (the spread between the backends), and the continued runs
// must end no farther from the CPU's straight run than twice that (the restarted ones share N
// steps with one side, so a history lost or a clock not restored would show as a larger jump).
TEST(GpuParity, CheckpointContinuesOnTheOtherBackend) {
    if (!gpuPresent()) GTEST_SKIP() << "no usable GPU";
    ScratchDir scratch;
    const std::filesystem::path& dir = scratch.path();
    auto run = [&](const std::string& first, const std::string& second, const std::string& out) {
        CheckpointScene sc;
        sc.backend = first;
        const std::string mid = (dir / ("mid_" + first + ".ckpt")).string();
        {
            DEMSolver sim;
            buildCheckpointScene(sim, sc);
            checkpointScenePhase1(sim, sc, N);
            sim.WriteCheckpoint(mid);
        }
        sc.backend = second;
        DEMSolver sim;
        buildCheckpointScene(sim, sc);
        EXPECT_EQ(sim.GetBackend(), second);
        sim.ReadCheckpoint(mid);
        for (size_t k = 0; k < N; k++) sim.DoStepDynamics();
        sim.WriteCheckpoint(out);
        return savedState(out, 0, 0);
    };
    const Saved cpu = run("cpu", "cpu", (dir / "cc.ckpt").string());
    const Saved gpu = run("cuda", "cuda", (dir / "gg.ckpt").string());
    const Saved cpuThenGpu = run("cpu", "cuda", (dir / "cg.ckpt").string());
    const Saved gpuThenCpu = run("cuda", "cpu", (dir / "gc.ckpt").string());
    auto maxDistance = [](const Saved& a, const Saved& b) {
        double d = 0.0;
        for (size_t o = 0; o < a.state.numClumps; o++)
            d = std::max(d, length(ownerCentre(a.state, o) - ownerCentre(b.state, o)));
        return d;
    };
    const double spread = maxDistance(gpu, cpu);
    std::printf("GPU vs CPU after %zu steps: %.3g m; CPU->GPU restart %.3g m, GPU->CPU restart %.3g m\n", 2 * N,
                spread, maxDistance(cpuThenGpu, cpu), maxDistance(gpuThenCpu, cpu));
    EXPECT_EQ(cpuThenGpu.time, cpu.time);
    EXPECT_EQ(gpuThenCpu.step, cpu.step);
    EXPECT_LE(maxDistance(cpuThenGpu, cpu), 2.0 * spread + 1e-7);
    EXPECT_LE(maxDistance(gpuThenCpu, cpu), 2.0 * spread + 1e-7);
    EXPECT_GT(histories(cpuThenGpu.state).size(), 20u);
}
