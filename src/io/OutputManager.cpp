#include "io/OutputManager.h"

#include <deme/Error.h>

#include "io/AtomicFile.h"
#include "io/CsvFrameWriter.h"
#include "io/FrameStaging.h"
#include "io/PngEncoder.h"
#include "io/SnapshotScene.h"
#include "io/VtkWriter.h"

namespace deme {

namespace {

// Takes a job's staged bytes off the count when the job ends (written or failed).
struct StagedBytesRelease {
    std::atomic<size_t>& staged;
    size_t bytes;
    ~StagedBytesRelease() { staged -= bytes; }
};

const char* kindName(OutputKind k) {
    static const char* names[] = {"spheres", "clumps", "contacts", "meshes", "stress"};
    return names[(int)k];
}

// Legacy VTK of a staged mesh frame: the writer's arrays (points, index triples, owners).
void writeFrameLegacyVtk(const OutputFrame& f, const std::string& path) {
    const FrameColumn& pts = f.columns[f.pointsColumn];
    std::vector<double3> points(f.rows);
    for (size_t i = 0; i < f.rows; i++) {
        const double* p = pts.values<double>() + 3 * i;
        points[i] = make_double3(p[0], p[1], p[2]);
    }
    const size_t nT = f.cells();
    std::vector<int3> tris(nT);
    std::vector<int> owner(nT);
    for (size_t t = 0; t < nT; t++) {
        tris[t] = make_int3((int)(3 * t), (int)(3 * t + 1), (int)(3 * t + 2));
        owner[t] = f.cellColumns[0].values<int32_t>()[t];
    }
    writeVtkTriangles(path, points, tris, owner, f.call);
}

}  // namespace

void OutputManager::write(OutputKind kind, const Simulation& sim, const std::string& path, const char* call) {
    m_queue.wait(call);
    if (path.empty()) throwError(call, "empty file name");
    // Staged here, between steps; from here on the writer thread needs nothing of the simulation.
    submit(kind,
           std::make_shared<OutputFrame>(kind == OutputKind::SPHERES    ? stageSphereFrame(sim)
                                         : kind == OutputKind::CLUMPS   ? stageClumpFrame(sim)
                                         : kind == OutputKind::CONTACTS ? stageContactFrame(sim)
                                                                        : stageMeshFrame(sim)),
           path, call);
}

void OutputManager::writeStressField(const Simulation& sim, const std::string& path, const double3& lo,
                                     const double3& hi, const unsigned int n[3], const char* call) {
    m_queue.wait(call);
    if (path.empty()) throwError(call, "empty file name");
    submit(OutputKind::STRESS, std::make_shared<OutputFrame>(stageStressFrame(sim, lo, hi, n, call)), path, call);
}

void OutputManager::submit(OutputKind kind, std::shared_ptr<OutputFrame> frame, const std::string& path,
                           const char* call) {
    PvdSeries* series = m_series[(int)kind].get();
    const bool vtu = isVtu(kind);
    if (series && !vtu)
        throwError(call, "the series \"" + series->path() + "\" lists VTU files, but the output format is " +
                             (kind == OutputKind::MESHES ? "VTK: call SetMeshOutputFormat(\"VTU\")"
                                                         : "CSV: call SetOutputFormat(\"VTU\")") +
                             " (or end the series with SetOutputSeries(\"" + kindName(kind) + "\", \"\"))");
    const VtuOptions vo = options.vtuOptions;
    const bool mesh = kind == OutputKind::MESHES;
    size_t bytes = 0;
    for (const FrameColumn& c : frame->columns) bytes += c.bytes();
    for (const FrameColumn& c : frame->cellColumns) bytes += c.bytes();
    m_stagedBytes += bytes;
    std::atomic<size_t>* staged = &m_stagedBytes;
    m_queue.submit([frame, path, vtu, vo, mesh, series, bytes, staged]() {
        const StagedBytesRelease release{*staged, bytes};
        if (mesh && !vtu) {
            writeFrameLegacyVtk(*frame, path);
        } else {
            AtomicFile file(path, frame->call);
            if (vtu)
                writeFrameVtu(*frame, vo, file);
            else
                writeFrameCsv(*frame, file);
            file.commit();
        }
        // Only a frame that is in place joins the series.
        if (series) series->add(path, frame->time, frame->call);
    });
}

void OutputManager::writeSnapshot(const Simulation& sim, const std::string& path, const SnapshotOptions& o,
                                  const char* call) {
    m_queue.wait(call);
    if (path.empty()) throwError(call, "empty file name");
    validateSnapshotOptions(o, call);
    // Rendered here (with the OpenMP threads, between steps); encoded and written in the background.
    auto img = std::make_shared<RgbImage>(renderSnapshot(stageSnapshotScene(sim, o, call), o));
    const std::string c = call;
    const size_t bytes = img->rgb.size();
    m_stagedBytes += bytes;
    std::atomic<size_t>* staged = &m_stagedBytes;
    m_queue.submit([img, path, c, bytes, staged]() {
        const StagedBytesRelease release{*staged, bytes};
        const std::vector<uint8_t> png = encodePng(img->width, img->height, img->rgb.data());
        AtomicFile file(path, c);
        file.write(png.data(), png.size());
        file.commit();
    });
}

void OutputManager::setSeries(OutputKind kind, const std::string& pvdPath, const char* call) {
    m_queue.wait(call);  // the writer thread may be adding to the series being replaced
    m_series[(int)kind] = pvdPath.empty() ? nullptr : std::make_unique<PvdSeries>(pvdPath);
}

}  // namespace deme
