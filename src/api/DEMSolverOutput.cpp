// DEMSolver's output calls: file formats and contents, the files themselves (written in the
// background by io/OutputManager), snapshots, and the progress report with its run summary.
#include <deme/DEMSolver.h>

#include <cmath>

#include "backend/cuda/DeviceBuffer.h"
#include "io/OutputManager.h"
#include "io/ProgressReporter.h"
#include "runtime/Simulation.h"

namespace deme {

// The format settings take effect with the next output call: a file already handed to the writer
// thread is written as it was staged.
void DEMSolver::SetOutputFormat(const std::string& format) {
    if (format != "CSV" && format != "VTU")
        throwError("SetOutputFormat", "unsupported format \"" + format + "\" (CSV, VTU)");
    m_output->options.vtu = format == "VTU";
}

void DEMSolver::SetVTUEncoding(const std::string& encoding) {
    if (encoding != "appended" && encoding != "base64")
        throwError("SetVTUEncoding", "unknown encoding \"" + encoding + "\" (appended, base64)");
    m_output->options.vtuOptions.base64 = encoding == "base64";
}

void DEMSolver::SetVTUCompression(const std::string& compression) {
    if (compression != "none" && compression != "zlib")
        throwError("SetVTUCompression", "unknown compression \"" + compression + "\" (none, zlib)");
    m_output->options.vtuOptions.zlib = compression == "zlib";
}

void DEMSolver::SetMeshOutputFormat(const std::string& format) {
    if (format != "VTK" && format != "VTU")
        throwError("SetMeshOutputFormat", "unsupported format \"" + format + "\" (VTK, VTU)");
    m_output->options.meshVtu = format == "VTU";
}

void DEMSolver::SetOutputContent(const std::string& content) {
    std::vector<std::string> items;
    std::string cur;
    for (char ch : content + " ") {
        if (ch == ' ' || ch == '|' || ch == ',') {
            if (!cur.empty()) items.push_back(cur);
            cur.clear();
        } else {
            cur += ch;
        }
    }
    SetOutputContent(items);
}

void DEMSolver::SetOutputContent(const std::vector<std::string>& content) {
    Settings& s = m_sim->settings;
    for (const auto& c : content) {
        if (c == "XYZ")
            continue;  // always written
        else if (c == "ABSV")
            s.outAbsv = true;
        else if (c == "VEL")
            s.outVel = true;
        else if (c == "ANG_VEL")
            s.outAngVel = true;
        else if (c == "FAMILY")
            s.outFamily = true;
        else if (c == "OWNER")
            s.outOwner = true;
        else if (c == "MAT")
            s.outMat = true;
        else if (c == "QUAT")
            s.outQuat = true;
        else
            throwError("SetOutputContent",
                       "unknown content \"" + c + "\" (XYZ, ABSV, VEL, ANG_VEL, FAMILY, OWNER, MAT, QUAT)");
    }
}

void DEMSolver::WriteSphereFile(const std::string& path) const {
    requireInitialized("WriteSphereFile");
    m_output->write(OutputKind::SPHERES, *m_sim, path, "WriteSphereFile");
}
void DEMSolver::WriteClumpFile(const std::string& path) const {
    requireInitialized("WriteClumpFile");
    m_output->write(OutputKind::CLUMPS, *m_sim, path, "WriteClumpFile");
}
void DEMSolver::WriteContactFile(const std::string& path) const {
    requireInitialized("WriteContactFile");
    m_output->write(OutputKind::CONTACTS, *m_sim, path, "WriteContactFile");
}
void DEMSolver::WriteMeshFile(const std::string& path) const {
    requireInitialized("WriteMeshFile");
    m_output->write(OutputKind::MESHES, *m_sim, path, "WriteMeshFile");
}
void DEMSolver::FlushOutput() const { m_output->flush("FlushOutput"); }

void DEMSolver::SetOutputSeries(const std::string& kind, const std::string& pvdPath) {
    const char* call = "SetOutputSeries";
    const OutputKind k = kind == "spheres"    ? OutputKind::SPHERES
                         : kind == "clumps"   ? OutputKind::CLUMPS
                         : kind == "contacts" ? OutputKind::CONTACTS
                         : kind == "meshes"   ? OutputKind::MESHES
                                              : throw Error(std::string(call) + ": unknown kind \"" + kind +
                                                            "\" (spheres, clumps, contacts, meshes)");
    m_output->setSeries(k, pvdPath, call);
}

void DEMSolver::WriteSnapshot(const std::string& path) const { WriteSnapshot(path, SnapshotOptions()); }
void DEMSolver::WriteSnapshot(const std::string& path, const SnapshotOptions& options) const {
    requireInitialized("WriteSnapshot");
    m_output->writeSnapshot(*m_sim, path, options, "WriteSnapshot");
}

// ---------------------------------------------------------------- progress and run summary
void DEMSolver::attachProgressHooks() {
    RunMonitor& monitor = m_sim->monitor();
    if (m_progressHook < 0)
        m_progressHook = monitor.addHook([this](const RunProgress& p) {
            m_progress->onProgress(p, m_sim->settings.verbosity, [this, &p] { return runSummary(p); });
            return false;
        });
}

void DEMSolver::SetProgressReport(bool enable, double intervalSeconds) {
    if (!(intervalSeconds > 0.0) || !std::isfinite(intervalSeconds))
        throwError("SetProgressReport", "the interval must be a positive number of seconds");
    m_progress->setEnabled(enable);
    m_progress->setInterval(intervalSeconds);
    // Off: no hook at all, so that a run without any watcher polls no clock.
    if (!enable && m_progressHook >= 0) {
        m_sim->monitor().removeHook(m_progressHook);
        m_progressHook = -1;
    }
    if (enable) attachProgressHooks();
}

void DEMSolver::SetProgressCallback(std::function<void(const RunProgress&)> callback) {
    RunMonitor& monitor = m_sim->monitor();
    if (m_callbackHook >= 0) monitor.removeHook(m_callbackHook);
    m_callbackHook = -1;
    m_progressCallback = std::move(callback);
    if (!m_progressCallback) return;
    m_callbackHook = monitor.addHook([this](const RunProgress& p) {
        if (m_callbackError) return true;
        try {
            m_progressCallback(p);
        } catch (...) {
            // Thrown again by the call once its step loop has stopped with the state consistent.
            m_callbackError = std::current_exception();
            return true;
        }
        return false;
    });
}

void DEMSolver::rethrowCallbackError() {
    if (!m_callbackError) return;
    std::exception_ptr e = m_callbackError;
    m_callbackError = nullptr;
    std::rethrow_exception(e);
}

RunSummary DEMSolver::runSummary(const RunProgress& p) const {
    RunSummary r;
    r.wallSeconds = p.wallSeconds;
    r.steps = p.stepsDone;
    r.simSeconds = (double)p.stepsDone * m_sim->settings.dt;
    r.spheres = p.spheres;
    r.sphereStepsPerSecond = p.wallSeconds > 0.0 ? (double)p.spheres * (double)p.stepsDone / p.wallSeconds : 0.0;
    // As GetAvgSphContacts, from counts the step loop keeps on the host (no download from the device).
    const size_t ss = m_sim->numSphereSphereContacts();
    r.contactsPerSphere = p.spheres ? (double)(2 * ss + (m_sim->numRealContacts() - ss)) / (double)p.spheres : 0.0;
    r.peakHostBytes = peakHostResidentBytes();
    r.onGpu = m_sim->settings.onGpu;
    if (r.onGpu) {
        r.deviceBytes = cuda::deviceBytesAllocated();
        r.deviceBytesPeak = cuda::deviceBytesAllocatedPeak();
    }
    return r;
}

RunSummary DEMSolver::GetRunSummary() const { return runSummary(m_sim->monitor().progress()); }

}  // namespace deme
