#include "io/OutputWriters.h"

#include <cstdio>
#include <memory>

#include <deme/Error.h>

#include "dynamics/ContactInputsGather.h"
#include "io/VtkWriter.h"
#include "runtime/Simulation.h"

namespace deme {

namespace {

struct FileCloser {
    void operator()(FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<FILE, FileCloser>;

File openForWriting(const std::string& path, const char* call) {
    File f(std::fopen(path.c_str(), "w"));
    if (!f) throwError(call, "cannot open \"" + path + "\" for writing");
    return f;
}

void finish(File& f, const std::string& path, const char* call) {
    if (std::ferror(f.get()) || std::fclose(f.release()) != 0) throwError(call, "error writing \"" + path + "\"");
}

// The owner wildcards' names as header columns, if EnableOwnerWildcardOutput asked for them.
void ownerWildcardHeader(FILE* f, const Simulation& sim) {
    if (!sim.settings.outOwnerWildcards) return;
    for (const std::string& name : sim.forceModel().ownerWildcards) std::fprintf(f, ",%s", name.c_str());
}

void ownerWildcardColumns(FILE* f, const Simulation& sim, size_t owner) {
    if (!sim.settings.outOwnerWildcards) return;
    for (const std::vector<float>& w : sim.state().wildcards.owner) std::fprintf(f, ",%.9g", w[owner]);
}

}  // namespace

void writeSphereCsv(const Simulation& sim, const std::string& path) {
    const char* call = "WriteSphereFile";
    const SimState& s = sim.state();
    const Settings& o = sim.settings;
    File f = openForWriting(path, call);
    std::fprintf(f.get(), "X,Y,Z,r");
    if (o.outAbsv) std::fprintf(f.get(), ",absv");
    if (o.outVel) std::fprintf(f.get(), ",v_x,v_y,v_z");
    if (o.outAngVel) std::fprintf(f.get(), ",w_x,w_y,w_z");
    if (o.outFamily) std::fprintf(f.get(), ",family");
    if (o.outOwner) std::fprintf(f.get(), ",owner");
    if (o.outMat) std::fprintf(f.get(), ",material");
    if (o.outQuat) std::fprintf(f.get(), ",Qw,Qx,Qy,Qz");
    ownerWildcardHeader(f.get(), sim);
    std::fprintf(f.get(), "\n");
    // Rows in user order: owners as added, each owner's spheres in template order.
    for (size_t u = 0; u < s.numClumps; u++) {
        const bodyID_t ow = s.ownerUserToInternal[u];
        for (uint32_t i = s.ownerSphereStart[ow]; i < s.ownerSphereStart[ow + 1]; i++) {
            const float4 q = s.owners.oriQ[ow];
            const double3 p = s.cache.spherePos[i];
            const float3 w = rotateToGlobal(q, s.owners.angVel[ow]);
            // A sphere's velocity includes its owner's spin about the owner centre.
            const float3 v = s.owners.vel[ow] + cross(w, rotateToGlobal(q, s.spheres.relPos[i]));
            std::fprintf(f.get(), "%.9g,%.9g,%.9g,%.9g", p.x, p.y, p.z, s.spheres.radius[i]);
            if (o.outAbsv) std::fprintf(f.get(), ",%.9g", length(v));
            if (o.outVel) std::fprintf(f.get(), ",%.9g,%.9g,%.9g", v.x, v.y, v.z);
            if (o.outAngVel) std::fprintf(f.get(), ",%.9g,%.9g,%.9g", w.x, w.y, w.z);
            if (o.outFamily) std::fprintf(f.get(), ",%u", (unsigned)s.owners.family[ow]);
            if (o.outOwner) std::fprintf(f.get(), ",%u", (unsigned)s.ownerInternalToUser[ow]);
            if (o.outMat) std::fprintf(f.get(), ",%u", (unsigned)s.spheres.material[i]);
            if (o.outQuat) std::fprintf(f.get(), ",%.9g,%.9g,%.9g,%.9g", q.w, q.x, q.y, q.z);
            ownerWildcardColumns(f.get(), sim, ow);
            std::fprintf(f.get(), "\n");
        }
    }
    finish(f, path, call);
}

void writeClumpCsv(const Simulation& sim, const std::string& path) {
    const char* call = "WriteClumpFile";
    const SimState& s = sim.state();
    File f = openForWriting(path, call);
    std::fprintf(f.get(), "owner,X,Y,Z,Qw,Qx,Qy,Qz,v_x,v_y,v_z,w_x,w_y,w_z,mass,family");
    ownerWildcardHeader(f.get(), sim);
    std::fprintf(f.get(), "\n");
    for (size_t u = 0; u < s.numClumps; u++) {
        const size_t o = s.ownerUserToInternal[u];
        const double3 p = ownerPosition(s, (bodyID_t)o);
        const float4 q = s.owners.oriQ[o];
        const float3 v = s.owners.vel[o], w = s.owners.angVel[o];
        std::fprintf(f.get(), "%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%u", u, p.x,
                     p.y, p.z, q.w, q.x, q.y, q.z, v.x, v.y, v.z, w.x, w.y, w.z, sim.ownerMass(o),
                     (unsigned)s.owners.family[o]);
        ownerWildcardColumns(f.get(), sim, o);
        std::fprintf(f.get(), "\n");
    }
    finish(f, path, call);
}

void writeContactCsv(const Simulation& sim, const std::string& path) {
    const char* call = "WriteContactFile";
    const SimState& s = sim.state();
    File f = openForWriting(path, call);
    std::fprintf(f.get(), "type,geomA,geomB,ownerA,ownerB,X,Y,Z,f_x,f_y,f_z,n_x,n_y,n_z,overlap\n");
    for (size_t c = 0; c < s.contacts.size(); c++) {
        ContactInputs in;
        gatherContactInputs(s, c, (float)sim.time(), (float)sim.settings.dt, in);
        const uint8_t type = s.contacts.type[c];
        const float3 F = s.contacts.force[c];
        // Pairs in contact, and pairs a custom model gives a force at a distance.
        const bool counts = type != SPHERE_TRIANGLE || (s.contacts.meshState[c] & 1u);
        const bool loaded = F.x != 0.f || F.y != 0.f || F.z != 0.f;
        if (!counts || !(in.overlapDepth > 0.0 || loaded)) continue;
        const bool ss = type == SPHERE_SPHERE;
        // Ids in user order: spheres as laid out by the templates of the clumps as added.
        const unsigned long geomA = s.sphereInternalToUser[in.AGeo];
        const unsigned long geomB = ss                          ? s.sphereInternalToUser[in.BGeo]
                                    : type == SPHERE_ANALYTICAL ? in.BGeo - (unsigned long)s.analyticalIdBase()
                                                                : in.BGeo - (unsigned long)s.triangleIdBase();
        std::fprintf(f.get(), "%s,%lu,%lu,%u,%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", ss ? "SS" : type == SPHERE_ANALYTICAL ? "SA" : "SM",
                     geomA, geomB, (unsigned)s.ownerInternalToUser[in.AOwner],
                     (unsigned)s.ownerInternalToUser[in.BOwner], in.contactPnt.x, in.contactPnt.y, in.contactPnt.z, F.x,
                     F.y, F.z, in.B2A.x, in.B2A.y, in.B2A.z, in.overlapDepth);
    }
    finish(f, path, call);
}

void writeMeshVtk(const Simulation& sim, const std::string& path) {
    const SimState& s = sim.state();
    const size_t nT = s.triangles.size();
    std::vector<int3> tris(nT);
    std::vector<int> owner(nT);
    for (size_t t = 0; t < nT; t++) {
        tris[t] = make_int3((int)(3 * t), (int)(3 * t + 1), (int)(3 * t + 2));
        owner[t] = (int)s.ownerInternalToUser[s.triangles.owner[t]];
    }
    writeVtkTriangles(path, s.cache.triVert, tris, owner, "WriteMeshFile");
}

}  // namespace deme
