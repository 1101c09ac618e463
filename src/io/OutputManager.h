// The solver's output: stages a frame on the calling thread (between steps), then has the writer
// thread encode and write it (CSV, VTU or legacy VTK; PNG for snapshots) to a temporary name and
// rename it, and add it to its .pvd series if one is set. Every call first waits for the previous
// file and reports its failure (docs/paraview.md, "Output in the background").
#pragma once

#include <array>
#include <atomic>
#include <deme/VectorTypes.h>
#include <memory>
#include <string>

#include <deme/Snapshot.h>

#include "io/OutputQueue.h"
#include "io/PvdSeries.h"
#include "io/VtuWriter.h"

namespace deme {

class Simulation;

enum class OutputKind { SPHERES = 0, CLUMPS = 1, CONTACTS = 2, MESHES = 3, STRESS = 4 };

struct OutputOptions {
    bool vtu = false;      // SetOutputFormat: "VTU" or "CSV" (default)
    bool meshVtu = false;  // SetMeshOutputFormat: "VTU" or "VTK" (legacy, default)
    VtuOptions vtuOptions;
};

class OutputManager {
  public:
    OutputOptions options;

    void write(OutputKind kind, const Simulation& sim, const std::string& path, const char* call);
    // The coarse-grained stress of the grains over a box split into n[0] x n[1] x n[2] cells
    // (WriteStressField; the sphere files' format, CSV or VTU).
    void writeStressField(const Simulation& sim, const std::string& path, const double3& lo, const double3& hi,
                          const unsigned int n[3], const char* call);
    void writeSnapshot(const Simulation& sim, const std::string& path, const SnapshotOptions& o, const char* call);
    // Frames of `kind` written from now on are listed in `pvdPath` (empty: no series).
    void setSeries(OutputKind kind, const std::string& pvdPath, const char* call);
    // Waits for the file being written; throws its failure.
    void flush(const char* call) { m_queue.wait(call); }
    // Bytes of the staged frame or image the writer thread holds now (MemoryGroup::OUTPUT).
    size_t stagedBytes() const { return m_stagedBytes.load(); }

  private:
    bool isVtu(OutputKind kind) const { return kind == OutputKind::MESHES ? options.meshVtu : options.vtu; }
    // Hands a staged frame of `kind` to the writer thread (and its series, if one is set).
    void submit(OutputKind kind, std::shared_ptr<OutputFrame> frame, const std::string& path, const char* call);
    // Declared before the queue, whose destructor waits for the job that may still add to a series.
    std::array<std::unique_ptr<PvdSeries>, 5> m_series;
    std::atomic<size_t> m_stagedBytes{0};
    OutputQueue m_queue;
};

}  // namespace deme
