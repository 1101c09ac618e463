#include "io/FrameStaging.h"

#include <vector>

#include "dynamics/ContactInputsGather.h"
#include "runtime/ContactForceView.h"
#include "runtime/Simulation.h"
#include "runtime/StressMeasure.h"
#include "state/ContactTypeOf.h"
#include "state/SphereIds.h"
#include "state/SphereLayout.h"

namespace deme {

namespace {

constexpr long PARALLEL_MIN_ROWS = 4096;  // below this the thread team costs more than the loop

void putPoint(FrameColumn& c, size_t row, const double3& p) {
    double* d = c.values<double>() + 3 * row;
    d[0] = p.x, d[1] = p.y, d[2] = p.z;
}
void put3(FrameColumn& c, size_t row, const float3& v) {
    float* d = c.values<float>() + 3 * row;
    d[0] = v.x, d[1] = v.y, d[2] = v.z;
}
void putQuat(FrameColumn& c, size_t row, const float4& q) {
    float* d = c.values<float>() + 4 * row;
    d[0] = q.w, d[1] = q.x, d[2] = q.y, d[3] = q.z;
}

OutputFrame newFrame(const Simulation& sim, const char* call, size_t rows) {
    OutputFrame f;
    f.call = call;
    f.time = sim.time();
    f.rows = rows;
    return f;
}

// Owner wildcard columns (EnableOwnerWildcardOutput), one Float32 array per wildcard.
std::vector<FrameColumn*> addOwnerWildcardColumns(OutputFrame& f, const Simulation& sim) {
    std::vector<FrameColumn*> cols;
    if (!sim.settings.outOwnerWildcards) return cols;
    for (const std::string& name : sim.forceModel().ownerWildcards)
        cols.push_back(&f.addColumn(name, {name}, ValueType::FLOAT32, f.rows));
    return cols;
}

void fillOwnerWildcards(const std::vector<FrameColumn*>& cols, const SimState& s, size_t row, size_t owner) {
    for (size_t w = 0; w < cols.size(); w++) cols[w]->values<float>()[row] = s.wildcards.owner[w][owner];
}

// Rows in user order over the ids still in use: ids of removed spheres (owners) leave no gap in the
// file, and clumps inserted during a run (ids after the external objects' and meshes') follow the
// earlier clumps. rowOf[u] for each live user id u; empty while the ids are 0..n-1 as assigned.
std::vector<uint32_t> sphereRows(const SimState& s) {
    std::vector<uint32_t> rowOf;
    if (userSphereCount(s) == s.spheres.size()) return rowOf;
    rowOf.assign(userSphereCount(s), 0);
    uint32_t row = 0;
    for (size_t u = 0; u < rowOf.size(); u++)
        if (sphereInternalId(s, u) != SimState::REMOVED_ID) rowOf[u] = row++;
    return rowOf;
}

// The user ids of the clumps, ascending.
std::vector<bodyID_t> clumpUserIds(const SimState& s) {
    std::vector<bodyID_t> users;
    users.reserve(s.numClumps);
    for (size_t u = 0; u < s.ownerUserToInternal.size(); u++) {
        const bodyID_t o = s.ownerUserToInternal[u];
        if (o != SimState::REMOVED_ID && o < s.numClumps) users.push_back((bodyID_t)u);
    }
    return users;
}

}  // namespace

OutputFrame stageSphereFrame(const Simulation& sim) {
    const SimState& s = sim.state();  // downloads from the device where it has moved on
    const Settings& o = sim.settings;
    const size_t n = s.spheres.size();
    const std::vector<uint32_t> rowOf = sphereRows(s);
    OutputFrame f = newFrame(sim, "WriteSphereFile", n);
    FrameColumn& xyz = f.addColumn("Points", {"X", "Y", "Z"}, ValueType::FLOAT64, n);
    f.pointsColumn = 0;
    FrameColumn& r = f.addColumn("r", {"r"}, ValueType::FLOAT32, n);
    FrameColumn* absv = o.outAbsv ? &f.addColumn("absv", {"absv"}, ValueType::FLOAT32, n) : nullptr;
    FrameColumn* vel = o.outVel ? &f.addColumn("v", {"v_x", "v_y", "v_z"}, ValueType::FLOAT32, n) : nullptr;
    FrameColumn* angVel = o.outAngVel ? &f.addColumn("w", {"w_x", "w_y", "w_z"}, ValueType::FLOAT32, n) : nullptr;
    FrameColumn* family = o.outFamily ? &f.addColumn("family", {"family"}, ValueType::UINT8, n) : nullptr;
    FrameColumn* owner = o.outOwner ? &f.addColumn("owner", {"owner"}, ValueType::INT32, n) : nullptr;
    FrameColumn* mat = o.outMat ? &f.addColumn("material", {"material"}, ValueType::UINT8, n) : nullptr;
    FrameColumn* quat = o.outQuat ? &f.addColumn("Q", {"Qw", "Qx", "Qy", "Qz"}, ValueType::FLOAT32, n) : nullptr;
    const std::vector<FrameColumn*> wild = addOwnerWildcardColumns(f, sim);
    const bool needVel = absv || vel;

    // Rows in user order (owners as added, each owner's spheres in template order), filled in the
    // state's own order: the state is then read front to back and only the rows are scattered,
    // about twice as fast for millions of spheres as gathering in row order.
#pragma omp parallel for schedule(static) if ((long)n > PARALLEL_MIN_ROWS)
    for (long i = 0; i < (long)n; i++) {
        const size_t k = rowOf.empty() ? sphereUserId(s, i) : rowOf[sphereUserId(s, i)];
        const bodyID_t ow = sphereOwner(s, i);
        const float4 q = s.owners.oriQ[ow];
        putPoint(xyz, k, sphereCentre(s, i));
        r.values<float>()[k] = s.spheres.radius[i];
        const float3 w = rotateToGlobal(q, s.owners.angVel[ow]);
        if (needVel) {
            // A sphere's velocity includes its owner's spin about the owner centre.
            const float3 v = s.owners.vel[ow] + cross(w, rotateToGlobal(q, sphereRelPos(s, i)));
            if (absv) absv->values<float>()[k] = length(v);
            if (vel) put3(*vel, k, v);
        }
        if (angVel) put3(*angVel, k, w);
        if (family) family->values<uint8_t>()[k] = s.owners.family[ow];
        if (owner) owner->values<int32_t>()[k] = (int32_t)s.ownerInternalToUser[ow];
        if (mat) mat->values<uint8_t>()[k] = s.spheres.material[i];
        if (quat) putQuat(*quat, k, q);
        fillOwnerWildcards(wild, s, k, ow);
    }
    return f;
}

OutputFrame stageClumpFrame(const Simulation& sim) {
    const SimState& s = sim.state();
    const std::vector<bodyID_t> users = clumpUserIds(s);
    const size_t n = users.size();
    OutputFrame f = newFrame(sim, "WriteClumpFile", n);
    FrameColumn& owner = f.addColumn("owner", {"owner"}, ValueType::INT32, n);
    FrameColumn& xyz = f.addColumn("Points", {"X", "Y", "Z"}, ValueType::FLOAT64, n);
    f.pointsColumn = 1;
    FrameColumn& quat = f.addColumn("Q", {"Qw", "Qx", "Qy", "Qz"}, ValueType::FLOAT32, n);
    FrameColumn& vel = f.addColumn("v", {"v_x", "v_y", "v_z"}, ValueType::FLOAT32, n);
    FrameColumn& angVel = f.addColumn("w", {"w_x", "w_y", "w_z"}, ValueType::FLOAT32, n);
    FrameColumn& mass = f.addColumn("mass", {"mass"}, ValueType::FLOAT32, n);
    FrameColumn& family = f.addColumn("family", {"family"}, ValueType::UINT8, n);
    const std::vector<FrameColumn*> wild = addOwnerWildcardColumns(f, sim);
#pragma omp parallel for schedule(static) if ((long)n > PARALLEL_MIN_ROWS)
    for (long u = 0; u < (long)n; u++) {
        const bodyID_t o = s.ownerUserToInternal[users[u]];
        owner.values<int32_t>()[u] = (int32_t)users[u];
        putPoint(xyz, u, ownerCentre(s, o));
        putQuat(quat, u, s.owners.oriQ[o]);
        put3(vel, u, s.owners.vel[o]);
        put3(angVel, u, s.owners.angVel[o]);
        mass.values<float>()[u] = sim.ownerMass(o);
        family.values<uint8_t>()[u] = s.owners.family[o];
        fillOwnerWildcards(wild, s, u, o);
    }
    return f;
}

OutputFrame stageContactFrame(const Simulation& sim) {
    const SimState& s = sim.stateWithContacts();
    const long nc = (long)s.contacts.size();
    const ContactForceView forces(s.contacts);
    const float time = (float)sim.time(), dt = (float)sim.settings.dt;
    // Pairs in contact, and pairs a custom model gives a force at a distance. Two passes (which
    // pairs, then their rows) keep both parallel and the rows in contact-set order.
    std::vector<uint8_t> keep(nc);
#pragma omp parallel for schedule(static) if (nc > PARALLEL_MIN_ROWS)
    for (long c = 0; c < nc; c++) {
        const uint8_t type = contactTypeAt(s, c);
        const float3 F = forces[c];
        const bool counts = type != SPHERE_TRIANGLE || (s.contacts.meshState[c] & 1u);
        const bool loaded = !isZero(F);
        bool k = counts && loaded;
        if (counts && !loaded) {
            ContactInputs in;
            gatherContactInputs(s, c, time, dt, in);
            k = in.overlapDepth > 0.0;
        }
        keep[c] = k;
    }
    std::vector<size_t> row(nc + 1, 0);
    for (long c = 0; c < nc; c++) row[c + 1] = row[c] + keep[c];
    const size_t n = row[nc];

    OutputFrame f = newFrame(sim, "WriteContactFile", n);
    FrameColumn& type = f.addColumn("type", {"type"}, ValueType::UINT8, n);
    type.labels = {"SS", "SA", "SM"};
    FrameColumn& geomA = f.addColumn("geomA", {"geomA"}, ValueType::INT32, n);
    FrameColumn& geomB = f.addColumn("geomB", {"geomB"}, ValueType::INT32, n);
    FrameColumn& ownerA = f.addColumn("ownerA", {"ownerA"}, ValueType::INT32, n);
    FrameColumn& ownerB = f.addColumn("ownerB", {"ownerB"}, ValueType::INT32, n);
    FrameColumn& point = f.addColumn("Points", {"X", "Y", "Z"}, ValueType::FLOAT64, n);
    f.pointsColumn = 5;
    FrameColumn& force = f.addColumn("f", {"f_x", "f_y", "f_z"}, ValueType::FLOAT32, n);
    FrameColumn& normal = f.addColumn("n", {"n_x", "n_y", "n_z"}, ValueType::FLOAT32, n);
    FrameColumn& overlap = f.addColumn("overlap", {"overlap"}, ValueType::FLOAT64, n);
#pragma omp parallel for schedule(static) if (nc > PARALLEL_MIN_ROWS)
    for (long c = 0; c < nc; c++) {
        if (!keep[c]) continue;
        const size_t k = row[c];
        ContactInputs in;
        gatherContactInputs(s, c, time, dt, in);
        const uint8_t t = contactTypeAt(s, c);
        // Ids in user order: spheres as laid out by the templates of the clumps as added; the other
        // side's component (analytical) or triangle index counted from the first of its kind.
        const bool ss = t == SPHERE_SPHERE;
        type.values<uint8_t>()[k] = ss ? CONTACT_SS : t == SPHERE_ANALYTICAL ? CONTACT_SA : CONTACT_SM;
        geomA.values<int32_t>()[k] = (int32_t)sphereUserId(s, in.AGeo);
        geomB.values<int32_t>()[k] = (int32_t)(ss                       ? sphereUserId(s, in.BGeo)
                                               : t == SPHERE_ANALYTICAL ? in.BGeo - s.analyticalIdBase()
                                                                        : in.BGeo - s.triangleIdBase());
        ownerA.values<int32_t>()[k] = (int32_t)s.ownerInternalToUser[in.AOwner];
        ownerB.values<int32_t>()[k] = (int32_t)s.ownerInternalToUser[in.BOwner];
        putPoint(point, k, in.contactPnt);
        put3(force, k, forces[c]);
        put3(normal, k, in.B2A);
        overlap.values<double>()[k] = in.overlapDepth;
    }
    return f;
}

OutputFrame stageMeshFrame(const Simulation& sim) {
    const SimState& s = sim.state();
    const size_t nT = s.triangles.size();
    OutputFrame f = newFrame(sim, "WriteMeshFile", 3 * nT);
    f.triangleCells = true;
    FrameColumn& xyz = f.addColumn("Points", {"X", "Y", "Z"}, ValueType::FLOAT64, 3 * nT);
    f.pointsColumn = 0;
    FrameColumn& owner = f.addColumn("owner", {"owner"}, ValueType::INT32, nT, true);
    for (size_t t = 0; t < nT; t++) {
        for (int k = 0; k < 3; k++) putPoint(xyz, 3 * t + k, s.cache.triVert[3 * t + k]);
        owner.values<int32_t>()[t] = (int32_t)s.ownerInternalToUser[s.triangles.owner[t]];
    }
    return f;
}

OutputFrame stageStressFrame(const Simulation& sim, const double3& lo, const double3& hi, const unsigned int n[3],
                             const char* call) {
    const std::vector<StressTensor> cells = measureStressField(sim.stateWithContacts(), lo, hi, n);
    OutputFrame f = newFrame(sim, call, cells.size());
    FrameColumn& xyz = f.addColumn("points", {"X", "Y", "Z"}, ValueType::FLOAT64, f.rows);
    f.pointsColumn = 0;
    auto tensorNames = [](const std::string& p) {
        std::vector<std::string> names;
        for (const char* ij : {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"}) names.push_back(p + ij);
        return names;
    };
    FrameColumn& total = f.addColumn("stress", tensorNames("s"), ValueType::FLOAT64, f.rows);
    FrameColumn& contact = f.addColumn("contact_stress", tensorNames("c"), ValueType::FLOAT64, f.rows);
    FrameColumn& kinetic = f.addColumn("kinetic_stress", tensorNames("k"), ValueType::FLOAT64, f.rows);
    FrameColumn& pressure = f.addColumn("pressure", {"pressure"}, ValueType::FLOAT64, f.rows);
    FrameColumn& grains = f.addColumn("grains", {"grains"}, ValueType::INT32, f.rows);
    const double3 cell = make_double3((hi.x - lo.x) / n[0], (hi.y - lo.y) / n[1], (hi.z - lo.z) / n[2]);
    for (size_t c = 0; c < cells.size(); c++) {
        const size_t i = c % n[0], j = (c / n[0]) % n[1], k = c / ((size_t)n[0] * n[1]);
        putPoint(xyz, c,
                 make_double3(lo.x + (i + 0.5) * cell.x, lo.y + (j + 0.5) * cell.y, lo.z + (k + 0.5) * cell.z));
        for (int q = 0; q < 9; q++) {
            total.values<double>()[9 * c + q] = cells[c].total[q];
            contact.values<double>()[9 * c + q] = cells[c].contact[q];
            kinetic.values<double>()[9 * c + q] = cells[c].kinetic[q];
        }
        pressure.values<double>()[c] = cells[c].Pressure();
        grains.values<int32_t>()[c] = (int32_t)cells[c].grains;
    }
    return f;
}

}  // namespace deme
