// SMALL-SYSTEMS: the lab-scale runs of calibration sweeps, where a GPU is limited by what every step
// pays in launches and host synchronisations rather than by bandwidth.
//   small_systems drum|impact [warm steps] [timed steps] [backend] [auto|sync|async] [solvers]
// drum:   a drum turning at 2 rad/s about y (R = 0.1 m, 60 mm long), 8,000 spheres of r = 2 mm under
//         30,000 of r = 1 mm, dt = 0.8 us; warm-up default 20,000 steps (the lattice collapses into
//         a bed and the drum starts dragging it), then the timed steps (default 20,000).
// impact: a 20 mm steel ball at 5 m/s into a bed of 25,000 spheres of r = 1 mm in a 98 x 60 mm box,
//         dt = 0.5 us; the ball is held above the bed during the warm-up (default 40,000 steps, the
//         bed settles), then released at 5 m/s for the timed steps (default 200,000: 0.1 s).
// backend: cpu, cuda or auto (the solver's choice; default). Prints one JSON line: steps/s and
//         sphere-steps/s of the timed steps; DEME_BENCH_TIMING=1 adds the phase timings (of the whole
//         run) and the collaboration counters (of the first solver).
// solvers: that many independent solvers of the case, each on its own thread, timed together (a
//         sweep on one GPU): the line adds total_steps_per_s over all of them; steps_per_s is the
//         first solver's.
// DEME_BENCH_MODEL: builtin (default), or the same Hertz-Mindlin model as a custom model's code
//         (compiled at Initialize): "snippet", called for every pair of the contact set as custom
//         models are by default, or "snippet-touching", not called for apart pairs
//         (DEMForceModel::SetCalledForApartPairs(false)). The line's "model" says which.
#include <deme/deme.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <thread>
#include <string>
#include <vector>

#include "BenchUtil.h"
#include "HertzMindlinSnippet.h"

using namespace deme;

namespace {

std::shared_ptr<DEMMaterial> grainMaterial(DEMSolver& sim) {
    return sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
}

float sphereMass(double r, double density) { return (float)(density * 4.0 / 3.0 * PI * r * r * r); }

// The `count` lowest points of an HCP lattice of spacing `spacing` inside the drum's circle (radius
// `inner` about the y axis) above height zMin, for |y| < halfLen: the grains fill the drum from below.
std::vector<float3> lowestInDrum(float spacing, float inner, float halfLen, float zMin, size_t count) {
    HCPSampler sampler(spacing);
    std::vector<float3> pts =
        sampler.SampleBox(make_float3(0, 0, 0), make_float3(inner, halfLen - spacing / 2, inner));
    pts.erase(std::remove_if(pts.begin(), pts.end(),
                             [&](const float3& p) { return p.z < zMin || p.x * p.x + p.z * p.z > inner * inner; }),
              pts.end());
    std::sort(pts.begin(), pts.end(), [](const float3& a, const float3& b) { return a.z < b.z; });
    if (pts.size() < count) throw Error("small_systems: the drum holds only " + std::to_string(pts.size()) + " points");
    pts.resize(count);
    return pts;
}

void setUpDrum(DEMSolver& sim) {
    const float R = 0.1f, halfLen = 0.03f, rs = 0.001f, rl = 0.002f;
    auto mat = grainMaterial(sim);
    sim.InstructBoxDomainDimension(2 * R + 0.01f, 2 * halfLen + 0.01f, 2 * R + 0.01f);
    auto drum = sim.AddExternalObject();
    drum->AddCylinder(make_float3(0), make_float3(0, 1, 0), R, mat, 0);
    drum->AddPlane(make_float3(0, -halfLen, 0), make_float3(0, 1, 0), mat);
    drum->AddPlane(make_float3(0, halfLen, 0), make_float3(0, -1, 0), mat);
    drum->SetFamily(10);
    sim.SetFamilyPrescribedAngVel(10, "0", "2", "0");
    auto large = sim.LoadSphereType(sphereMass(rl, 2600), rl, mat);
    auto small = sim.LoadSphereType(sphereMass(rs, 2600), rs, mat);
    const std::vector<float3> bottom = lowestInDrum(2.01f * rl, R - 1.01f * rl, halfLen, -R, 8000);
    const std::vector<float3> top = lowestInDrum(2.01f * rs, R - 1.01f * rs, halfLen, bottom.back().z + 1.6f * rl, 30000);
    sim.AddClumps(large, bottom);
    sim.AddClumps(small, top);
    sim.SetInitTimeStep(0.8e-6);
    sim.SetMaxVelocity(1.f);
}

struct Impact {
    std::shared_ptr<DEMClumpBatch> ball;
};

Impact setUpImpact(DEMSolver& sim) {
    const float lx = 0.098f, ly = 0.060f, r = 0.001f, ballR = 0.01f;
    auto mat = grainMaterial(sim);
    auto steel = sim.LoadMaterial({{"E", 2e11}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
    sim.InstructBoxDomainDimension(lx, ly, 0.12f);
    sim.InstructBoxDomainBoundingBC("all", mat);
    auto grain = sim.LoadSphereType(sphereMass(r, 2600), r, mat);
    HCPSampler sampler(2.01f * r);
    std::vector<float3> pts = sampler.SampleBox(make_float3(0, 0, 0), make_float3(lx / 2 - 1.01f * r, ly / 2 - 1.01f * r, 0.06f - 1.01f * r));
    std::sort(pts.begin(), pts.end(), [](const float3& a, const float3& b) { return a.z < b.z; });
    if (pts.size() < 25000) throw Error("small_systems: the impact box holds only " + std::to_string(pts.size()));
    pts.resize(25000);
    sim.AddClumps(grain, pts);
    // The ball waits, held in a fixed family, 5 mm above the lattice's top until the timed steps.
    auto ballType = sim.LoadSphereType(sphereMass(ballR, 7800), ballR, steel);
    Impact im;
    im.ball = sim.AddClumps(ballType, {make_float3(0, 0, pts.back().z + r + ballR + 0.005f)});
    im.ball->SetFamily(1);
    sim.SetFamilyFixed(1);
    sim.SetInitTimeStep(0.5e-6);
    sim.SetMaxVelocity(5.f);
    return im;
}

// DEME_BENCH_MODEL's value (the header says what each is).
std::string forceModelChoice() {
    const char* v = std::getenv("DEME_BENCH_MODEL");
    const std::string m = v && *v ? v : "builtin";
    if (m != "builtin" && m != "snippet" && m != "snippet-touching")
        throw Error("small_systems: DEME_BENCH_MODEL must be builtin, snippet or snippet-touching, not \"" + m + "\"");
    return m;
}

// One run of the case: set up, warm-up, then `steps` timed steps; the timed part starts when `go`
// says so (several solvers start together) and the run reports to `done`.
struct Run {
    DEMSolver sim;
    std::shared_ptr<DEMTracker> ball;
    double dt = 0.0, wall = 0.0;
};

void setUp(Run& run, bool drum, const std::string& backend, const std::string& mode, unsigned long warm) {
    DEMSolver& sim = run.sim;
    sim.SetVerbosity("WARNING");
    if (backend != "auto") sim.SetBackend(backend);
    Impact impact;
    if (drum)
        setUpDrum(sim);
    else
        impact = setUpImpact(sim);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    if (mode != "auto") sim.SetSynchronousContactDetection(mode == "sync");
    // DEME_BENCH_FORCE_THREADS: the force pass's block size (SetForceCalcThreadsPerBlock), for sweeps.
    if (const char* t = std::getenv("DEME_BENCH_FORCE_THREADS")) sim.SetForceCalcThreadsPerBlock(std::atoi(t));
    const std::string model = forceModelChoice();
    if (model != "builtin") deme_bench::useHertzMindlinSnippet(sim)->SetCalledForApartPairs(model == "snippet");
    sim.Initialize();
    run.dt = drum ? 0.8e-6 : 0.5e-6;
    run.ball = drum ? nullptr : sim.Track(impact.ball);
    sim.DoDynamics((double)warm * run.dt);
    if (run.ball) {
        sim.ChangeFamily(1, 0);
        run.ball->SetVel(make_float3(0, 0, -5.f));
    }
}

}  // namespace

int main(int argc, char** argv) {
    const std::string which = argc > 1 ? argv[1] : "";
    if (which != "drum" && which != "impact") {
        std::fprintf(stderr,
                     "usage: %s drum|impact [warm steps] [timed steps] [cpu|cuda|auto] [auto|sync|async] [solvers]\n",
                     argv[0]);
        return 2;
    }
    const bool drum = which == "drum";
    // An argument left out or given as "" takes its default.
    auto arg = [&](int i) { return argc > i && *argv[i] ? std::string(argv[i]) : std::string(); };
    const unsigned long warm = arg(2).empty() ? (drum ? 20000 : 40000) : std::stoul(arg(2));
    const unsigned long steps = arg(3).empty() ? (drum ? 20000 : 200000) : std::stoul(arg(3));
    const std::string backend = arg(4).empty() ? "auto" : arg(4);
    const std::string mode = arg(5).empty() ? "auto" : arg(5);
    // Several independent solvers, each on its own thread (a calibration sweep on one GPU): set up
    // and warmed one after the other, then timed together.
    const unsigned long solvers = arg(6).empty() ? 1 : std::max(1ul, std::stoul(arg(6)));

    std::vector<std::unique_ptr<Run>> runs;
    for (unsigned long i = 0; i < solvers; i++) {
        runs.push_back(std::make_unique<Run>());
        setUp(*runs.back(), drum, backend, mode, warm);
    }
    const double t1 = deme_bench::seconds();
    std::vector<std::thread> threads;
    std::vector<std::string> failures(solvers);
    for (unsigned long i = 0; i < solvers; i++)
        threads.emplace_back([&, i] {
            Run& r = *runs[i];
            try {
                const double t = deme_bench::seconds();
                r.sim.DoDynamics((double)steps * r.dt);
                r.wall = deme_bench::seconds() - t;
            } catch (const std::exception& e) {
                failures[i] = e.what();
            }
        });
    for (std::thread& t : threads) t.join();
    const double wall = deme_bench::seconds() - t1;
    for (const std::string& f : failures)
        if (!f.empty()) {
            std::fprintf(stderr, "small_systems: %s\n", f.c_str());
            return 1;
        }
    DEMSolver& sim = runs[0]->sim;
    const std::shared_ptr<DEMTracker>& ball = runs[0]->ball;
    const double dt = runs[0]->dt;
    const double spheres = (double)sim.GetNumSpheres();

    deme_bench::JsonLine j;
    j.add("case", drum ? "SMALL-DRUM" : "SMALL-IMPACT")
        .add("backend", sim.GetBackend())
        .add("spheres", spheres)
        .add("dt", dt)
        .add("warmup_steps", (double)warm)
        .add("steps", (double)steps)
        .add("solvers", (double)solvers)
        .add("wall_s", wall)
        .add("steps_per_s", (double)steps / runs[0]->wall)
        .add("sphere_steps_per_s", spheres * (double)steps / runs[0]->wall)
        .add("total_steps_per_s", (double)solvers * (double)steps / wall)
        .add("total_sphere_steps_per_s", (double)solvers * spheres * (double)steps / wall)
        .add("model", forceModelChoice())
        .add("detection", sim.UsesAsyncContactDetection() ? "async" : "sync")
        .add("update_freq", (double)sim.GetUpdateFreq())
        .add("dT_wait_share", sim.GetDynamicsWaitShare())
        .add("contacts_per_sphere", sim.GetAvgSphContacts());
    if (ball) j.add("ball_z_m", ball->Pos().z).add("ball_vz_m_s", ball->Vel().z);
    deme_bench::printCase(j, sim);
    return 0;
}
