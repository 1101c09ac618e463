#include "io/Checkpoint.h"

#include <algorithm>

#include <deme/Error.h>

#include "codegen/Expression.h"
#include "codegen/FamilyCondition.h"
#include "io/CheckpointFile.h"
#include "io/CheckpointState.h"
#include "runtime/Simulation.h"

namespace deme {

namespace {

// ---------------------------------------------------------------- sections
// Each section is written by one function and read by its partner into a staging copy; nothing
// reaches the simulation before every section has been read (see readCheckpoint).
// A new section (e.g. counters of added and removed grains) is one pair here and one line in each
// of the two tables at the end of this file.

struct Staging {
    uint32_t version = CHECKPOINT_FORMAT_VERSION;  // the file's
    SceneFingerprint fingerprint;
    Simulation::Resumable clock;
    Settings settings;
    FamilyRules families;
    SimState state;
    // A version-1 file's travel: since the start, and at the contact set's snapshot (empty where the
    // set could not go on serving); made the travel since the snapshot once both are read.
    std::vector<double> travelSinceStart, travelAtSnapshot;
};

void writeFingerprint(const Simulation& sim, ByteWriter& out) {
    SceneFingerprint fp = sim.initialScene();
    forEachFingerprintField(fp, [&](const char*, uint64_t& v, bool) { out.value(v); });
}
void readFingerprint(ByteReader& in, Staging& st) {
    forEachFingerprintField(st.fingerprint, [&](const char* name, uint64_t& v, bool) { v = in.value<uint64_t>(name); });
}

void writeClock(const Simulation& sim, ByteWriter& out) {
    const Simulation::Resumable r = sim.resumable();
    out.value(r.time);
    out.value((uint64_t)r.step);
    out.value(r.lastMaxSpeed);
    out.value(r.realContacts);
    out.value(r.realSphereSphere);
    out.value((uint32_t)r.frequency.n);
    out.value((uint32_t)r.frequency.costN);
    out.value((uint32_t)r.frequency.latencyN);
    out.value(r.frequency.latency);
    out.value((uint64_t)r.contactSet.acsStep);
    out.value(r.contactSet.margin);
    out.value((uint8_t)r.contactSet.expired);
    out.value((uint8_t)r.contactSet.needDetection);
    out.value((uint8_t)r.contactSetResumable);
}
void readClock(ByteReader& in, Staging& st) {
    Simulation::Resumable& r = st.clock;
    r.time = in.value<double>("the simulated time");
    r.step = in.value<uint64_t>("the step counter");
    r.lastMaxSpeed = in.value<float>("the last step's largest speed");
    r.realContacts = in.value<uint64_t>("the contact count");
    r.realSphereSphere = in.value<uint64_t>("the sphere-sphere contact count");
    r.frequency.n = in.value<uint32_t>("n_max");
    r.frequency.costN = in.value<uint32_t>("n_max");
    r.frequency.latencyN = in.value<uint32_t>("n_max");
    r.frequency.latency = in.value<double>("the detection latency");
    r.contactSet.acsStep = in.value<uint64_t>("the contact set's snapshot step");
    r.contactSet.margin = in.value<double>("the contact set's margin");
    r.contactSet.expired = in.value<uint8_t>("the contact set's state") != 0;
    r.contactSet.needDetection = in.value<uint8_t>("the contact set's state") != 0;
    if (st.version >= 2)
        r.contactSetResumable = in.value<uint8_t>("the contact set's state") != 0;
    else
        in.array(st.travelAtSnapshot, "the travel at the contact set's snapshot");
}

// A version-1 file held every owner's travel since the start and at the contact set's snapshot;
// the state now holds their difference (the set goes on serving only where the file had both).
void travelSinceSnapshotOfVersion1(Staging& st) {
    std::vector<float>& travel = st.state.owners.travel;
    const bool resumable = st.travelAtSnapshot.size() == travel.size() && st.travelSinceStart.size() == travel.size();
    for (size_t o = 0; o < travel.size(); o++)
        travel[o] = resumable ? (float)std::max(st.travelSinceStart[o] - st.travelAtSnapshot[o], 0.0) : 0.f;
    st.clock.contactSetResumable = resumable;
}

// The settings a script may change between DoDynamics calls and that change the steps. How the run
// is executed (backend, threads, detection mode, output) is the restarted script's choice.
void writeSettings(const Simulation& sim, ByteWriter& out) {
    const Settings& s = sim.settings;
    out.value(s.dt);
    out.value(s.gravity);
    out.value(s.errorOutVelocity);
    out.value(s.maxVelocity);
    out.value(s.safetyMultiplier);
    out.value(s.safetyAdder);
    out.bytes(s.familyExtraMargin, sizeof(s.familyExtraMargin));
    out.value((uint8_t)s.removeLeavingClumps);  // SetDomainExitPolicy
}
void readSettings(ByteReader& in, Staging& st) {
    Settings& s = st.settings;
    s.dt = in.value<double>("the time step");
    s.gravity = in.value<float3>("gravity");
    s.errorOutVelocity = in.value<float>("the error-out velocity");
    s.maxVelocity = in.value<float>("the expected largest velocity");
    s.safetyMultiplier = in.value<float>("the margin's safety multiplier");
    s.safetyAdder = in.value<float>("the margin's safety adder");
    std::memcpy(s.familyExtraMargin, in.take(sizeof(s.familyExtraMargin), "the family margins"),
                sizeof(s.familyExtraMargin));
    s.removeLeavingClumps = in.value<uint8_t>("the domain exit policy") != 0;
}

// Fixed families, prescribed motions (as the expressions' text) and the contact mask: all may
// change after Initialize.
void writeFamilies(const Simulation& sim, ByteWriter& out) {
    out.bytes(sim.families.contactMask(), NUM_FAMILIES * NUM_FAMILIES);
    for (unsigned int f = 0; f < NUM_FAMILIES; f++) {
        const FamilyMotion& m = sim.families.motion(f);
        out.value((uint8_t)m.fixed);
        for (int i = 0; i < 3; i++) {
            out.value((uint8_t)m.linPrescribed[i]);
            out.text(m.lin[i].text());
            out.value((uint8_t)m.angPrescribed[i]);
            out.text(m.ang[i].text());
        }
    }
    // Family changes on conditions (ChangeFamilyWhen), in the order they are checked.
    out.value((uint32_t)sim.families.conditions().size());
    for (const FamilyCondition& c : sim.families.conditions()) {
        out.value(c.from);
        out.value(c.to);
        out.text(c.when.text());
    }
}
void readFamilies(ByteReader& in, Staging& st, const std::string& call) {
    const uint8_t* mask = reinterpret_cast<const uint8_t*>(in.take(NUM_FAMILIES * NUM_FAMILIES, "the contact mask"));
    for (unsigned int a = 0; a < NUM_FAMILIES; a++)
        for (unsigned int b = a; b < NUM_FAMILIES; b++) st.families.setContact(a, b, mask[a * NUM_FAMILIES + b] != 0);
    auto expression = [&](bool prescribed, const std::string& text) {
        return prescribed && !text.empty() ? Expression::parse(text, {"t"}, call) : Expression();
    };
    for (unsigned int f = 0; f < NUM_FAMILIES; f++) {
        FamilyMotion& m = st.families.motion(f);
        m.fixed = in.value<uint8_t>("a family rule") != 0;
        for (int i = 0; i < 3; i++) {
            m.linPrescribed[i] = in.value<uint8_t>("a family rule") != 0;
            m.lin[i] = expression(m.linPrescribed[i], in.text("a prescribed velocity"));
            m.angPrescribed[i] = in.value<uint8_t>("a family rule") != 0;
            m.ang[i] = expression(m.angPrescribed[i], in.text("a prescribed velocity"));
        }
    }
    st.families.conditions().clear();
    const uint32_t nConditions = in.value<uint32_t>("the family change count");
    for (uint32_t k = 0; k < nConditions; k++) {
        FamilyCondition c;
        c.from = in.value<family_t>("a family change");
        c.to = in.value<family_t>("a family change");
        c.when = Expression::parseCondition(in.text("a family change condition"), familyConditionVariables(), call);
        st.families.conditions().push_back(std::move(c));
    }
}

// The sections in file order; every one must be present when reading.
struct SectionDef {
    const char* name;
    void (*write)(const Simulation&, ByteWriter&);
};
const SectionDef SECTIONS[] = {
    {"fingerprint", writeFingerprint},
    {"clock", writeClock},
    {"settings", writeSettings},
    {"families", writeFamilies},
    {"state", [](const Simulation& sim, ByteWriter& out) { writeStateSection(sim.wholeState(), out); }},
};

void readSection(const std::string& name, ByteReader& in, Staging& st, const Simulation& sim,
                 const std::string& call, const std::string& path) {
    if (name == "fingerprint") {
        readFingerprint(in, st);
        // Before the state: a checkpoint of another scene is named as such, not by its arrays.
        const std::string diff = fingerprintMismatch(st.fingerprint, sim.initialScene());
        if (!diff.empty())
            throwError(call, "\"" + path + "\" is a checkpoint of another scene: " + diff +
                                 " (the restarted script must build the same scene up to Initialize())");
    } else if (name == "clock")
        readClock(in, st);
    else if (name == "settings")
        readSettings(in, st);
    else if (name == "families")
        readFamilies(in, st, call);
    else if (name == "state")
        readStateSection(in, st.state, call, path, st.version, st.travelSinceStart);
    if (name != "state" && !in.atEnd()) in.malformed("section \"" + name + "\" has bytes after its end");
}

}  // namespace

void writeCheckpoint(const Simulation& sim, const std::string& path, const std::string& call) {
    CheckpointSections sections;
    for (const SectionDef& d : SECTIONS) {
        ByteWriter w;
        d.write(sim, w);
        sections.add(d.name, std::move(w.buffer()));
    }
    writeCheckpointFile(path, sections, call);
}

void readCheckpoint(Simulation& sim, const std::string& path, const std::string& call) {
    const CheckpointSections sections = readCheckpointFile(path, call);
    Staging st;
    st.version = sections.version;
    st.settings = sim.settings;
    st.families = sim.families;
    bool seen[sizeof(SECTIONS) / sizeof(SECTIONS[0])] = {};
    // The fingerprint first, wherever it is in the file.
    std::vector<const std::pair<std::string, std::string>*> order;
    for (const auto& s : sections.list) (s.first == "fingerprint" ? order.insert(order.begin(), &s) : order.insert(order.end(), &s));
    for (const auto* s : order) {
        size_t k = 0;
        while (k < std::size(SECTIONS) && s->first != SECTIONS[k].name) k++;
        if (k == std::size(SECTIONS))
            throwError(call, "\"" + path + "\" has a section \"" + s->first +
                                 "\" this build does not know (written by a newer version of the engine?)");
        seen[k] = true;
        if (s->first == "state") st.state = sim.state();  // a copy: sizes of what is not stored stay valid (the contacts are all read)
        ByteReader in(s->second.data(), s->second.size(), call, path);
        readSection(s->first, in, st, sim, call, path);
    }
    for (size_t k = 0; k < std::size(SECTIONS); k++)
        if (!seen[k]) throwError(call, "\"" + path + "\" is corrupted: it has no section \"" + SECTIONS[k].name + "\"");

    if (st.version == 1) travelSinceSnapshotOfVersion1(st);

    // Everything read and checked: only now does the simulation change.
    sim.settings = st.settings;
    sim.families = st.families;
    sim.restore(std::move(st.state), st.clock);
}

}  // namespace deme
