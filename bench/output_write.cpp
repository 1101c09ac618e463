// OUTPUT-WRITE: how long a sphere frame takes to stage (copy out of the state) and to write, per
// format. One JSON line per case.
//   output_write staged <spheres> <dir>   a frame of that many spheres built directly (no solver), then
//                                         written as VTU in each encoding and as CSV
//   output_write solver <spheres> <dir> [steps]  a real solver's frame: WriteSphereFile (staging, on
//                                         the caller's thread) and FlushOutput (the writer thread's
//                                         work), and steps taken while the writer works against steps alone
// White-box for the staged case: it fills io/OutputFrame and calls the writers directly.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include <deme/deme.h>

#include "BenchUtil.h"
#include "io/AtomicFile.h"
#include "io/CsvFrameWriter.h"
#include "io/VtuWriter.h"

using namespace deme;
using namespace deme_bench;
namespace fs = std::filesystem;

namespace {

std::string device() { return cpuName() + " x " + std::to_string(std::thread::hardware_concurrency()) + " threads"; }

// Positions of a random bed (doubles, as the state's sphere centres), radii, speeds and velocities.
struct Source {
    std::vector<double> xyz;
    std::vector<float> r, v;
    explicit Source(size_t n) : xyz(3 * n), r(n), v(3 * n) {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (size_t i = 0; i < 3 * n; i++) xyz[i] = u(rng), v[i] = (float)(u(rng) - 0.5);
        for (size_t i = 0; i < n; i++) r[i] = (float)(0.001 + 0.0005 * u(rng));
    }
};

// As stageSphereFrame fills it, from plain arrays: the copy the solver makes between steps.
OutputFrame stage(const Source& s, bool velocities) {
    const size_t n = s.r.size();
    OutputFrame f;
    f.call = "bench";
    f.rows = n;
    FrameColumn& xyz = f.addColumn("Points", {"X", "Y", "Z"}, ValueType::FLOAT64, n);
    f.pointsColumn = 0;
    FrameColumn& r = f.addColumn("r", {"r"}, ValueType::FLOAT32, n);
    FrameColumn* absv = velocities ? &f.addColumn("absv", {"absv"}, ValueType::FLOAT32, n) : nullptr;
    FrameColumn* vel = velocities ? &f.addColumn("v", {"v_x", "v_y", "v_z"}, ValueType::FLOAT32, n) : nullptr;
#pragma omp parallel for schedule(static)
    for (long i = 0; i < (long)n; i++) {
        for (int k = 0; k < 3; k++) xyz.values<double>()[3 * i + k] = s.xyz[3 * i + k];
        r.values<float>()[i] = s.r[i];
        if (velocities) {
            const float* v = &s.v[3 * i];
            absv->values<float>()[i] = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int k = 0; k < 3; k++) vel->values<float>()[3 * i + k] = v[k];
        }
    }
    return f;
}

void line(const std::string& source, const std::string& format, const std::string& columns, size_t spheres,
          size_t bytes, double stage, double write) {
    JsonLine j;
    j.add("case", "OUTPUT-WRITE")
        .add("source", source)
        .add("device", device())
        .add("format", format)
        .add("columns", columns)
        .add("spheres", (double)spheres)
        .add("bytes", (double)bytes)
        .add("stage_s", stage)
        .add("write_s", write)
        .add("MB_per_s", (double)bytes / 1e6 / write)
        .add("peak_host_rss_mib", peakMemoryMiB());
    std::cout << j.str() << std::endl;
}

void staged(size_t n, const fs::path& dir, bool withCsv) {
    const Source src(n);
    for (bool velocities : {false, true}) {
        const std::string columns = velocities ? "XYZ r absv v" : "XYZ r";
        const double t0 = seconds();
        const OutputFrame f = stage(src, velocities);
        const double stageS = seconds() - t0;
        struct Variant {
            const char* name;
            bool base64, zlib;
        };
        for (const Variant& v : {Variant{"VTU appended raw", false, false}, Variant{"VTU base64", true, false},
                                 Variant{"VTU appended raw + zlib", false, true}, Variant{"VTU base64 + zlib", true, true}}) {
            VtuOptions o;
            o.base64 = v.base64, o.zlib = v.zlib;
            const fs::path p = dir / "bench_frame.vtu";
            const double t1 = seconds();
            AtomicFile file(p.string(), "bench");
            writeFrameVtu(f, o, file);
            file.commit();
            const double w = seconds() - t1;
            line("staged frame built directly", v.name, columns, n, fs::file_size(p), stageS, w);
            fs::remove(p);
        }
        if (withCsv) {
            const fs::path p = dir / "bench_frame.csv";
            const double t1 = seconds();
            AtomicFile file(p.string(), "bench");
            writeFrameCsv(f, file);
            file.commit();
            line("staged frame built directly", "CSV", columns, n, fs::file_size(p), stageS, seconds() - t1);
            fs::remove(p);
        }
    }
}

void solver(size_t n, const fs::path& dir, int steps) {
    const double t0 = seconds();
    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    sim.SetOutputContent("ABSV VEL");
    auto mat = sim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}});
    // A loose cube of spheres falling in a box: a realistic frame, few contacts at first.
    const float r = 0.001f;
    const int side = (int)std::ceil(std::cbrt((double)n));
    const float half = 0.5f * side * 2.2f * r;
    sim.InstructBoxDomainDimension(2.5f * half, 2.5f * half, 2.5f * half);
    std::vector<float3> pos;
    pos.reserve(n);
    for (size_t i = 0; i < n; i++)
        pos.push_back(make_float3(-half + 2.2f * r * (i % side), -half + 2.2f * r * (i / side % side),
                                  -half + 2.2f * r * (i / side / side)));
    sim.AddClumps(sim.LoadSphereType(1e-5f, r, mat), pos);
    sim.SetGravitationalAcceleration(make_float3(0, 0, -9.81f));
    sim.SetInitTimeStep(2e-6);
    sim.Initialize();
    const double init = seconds() - t0;
    sim.DoDynamics(20 * 2e-6);  // past the first contact detection

    sim.SetOutputFormat("VTU");
    const fs::path p = dir / "bench_solver_frame.vtu";
    // Rounds of: the steps alone; then a frame staged (WriteSphereFile) and the same number of steps
    // while the writer thread writes it, and what is left to wait for after them (FlushOutput);
    // then the write alone (staged and waited for at once). Best of three rounds each.
    double alone = 1e30, withWrite = 1e30, waited = 1e30, stage = 1e30, write = 1e30, firstStage = 0.0;
    size_t bytes = 0;
    for (int round = 0; round < 3; round++) {
        double t = seconds();
        sim.DoDynamics(steps * 2e-6);
        alone = std::min(alone, seconds() - t);
        t = seconds();
        sim.WriteSphereFile(p.string());
        const double st = seconds() - t;
        if (round == 0) firstStage = st;  // the frame's memory touched for the first time
        stage = std::min(stage, st);
        t = seconds();
        sim.DoDynamics(steps * 2e-6);
        withWrite = std::min(withWrite, seconds() - t);
        t = seconds();
        sim.FlushOutput();
        waited = std::min(waited, seconds() - t);
        t = seconds();
        sim.WriteSphereFile(p.string());
        const double st2 = seconds() - t;
        sim.FlushOutput();
        write = std::min(write, seconds() - t - st2);
        bytes = fs::file_size(p);
    }
    fs::remove(p);

    const RunSummary run = sim.GetRunSummary();
    JsonLine j;
    j.add("case", "OUTPUT-WRITE")
        .add("source", "solver frame (WriteSphereFile, FlushOutput)")
        .add("device", device())
        .add("format", "VTU appended raw")
        .add("columns", "XYZ r absv v")
        .add("spheres", (double)sim.GetNumSpheres())
        .add("bytes", (double)bytes)
        .add("stage_s", stage)
        .add("write_s", write)
        .add("MB_per_s", (double)bytes / 1e6 / write)
        .add("first_stage_s", firstStage)
        .add("initialize_s", init)
        .add("steps", (double)steps)
        .add("steps_alone_s", alone)
        .add("steps_while_writing_s", withWrite)
        .add("wait_after_steps_s", waited);
    addRunSummary(j, run);
    std::cout << j.str() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "staged";
    const size_t n = argc > 2 ? (size_t)std::atof(argv[2]) : 10000000;
    const fs::path dir = argc > 3 ? argv[3] : fs::temp_directory_path();
    try {
        if (mode == "staged")
            staged(n, dir, argc <= 4 || std::string(argv[4]) != "nocsv");
        else
            solver(n, dir, argc > 4 ? std::atoi(argv[4]) : 20);
    } catch (const std::exception& e) {
        std::cerr << e.what() << std::endl;
        return 1;
    }
    return 0;
}
