// DEMSolver's output options beyond the format (VTU encoding, series), FlushOutput, snapshots, and
// the progress report with its run summary. The files are written in the background by
// io/OutputManager.
#include <deme/DEMSolver.h>

#include <cmath>

#include "backend/cuda/DeviceBuffer.h"
#include "io/OutputManager.h"
#include "io/ProgressReporter.h"
#include "runtime/Simulation.h"

namespace deme {

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

void DEMSolver::FlushOutput() const { m_output->flush("FlushOutput"); }

void DEMSolver::SetOutputSeries(const std::string& kind, const std::string& pvdPath) {
    const char* call = "SetOutputSeries";
    const OutputKind k = kind == "spheres"    ? OutputKind::SPHERES
                         : kind == "clumps"   ? OutputKind::CLUMPS
                         : kind == "contacts" ? OutputKind::CONTACTS
                         : kind == "meshes"   ? OutputKind::MESHES
                         : kind == "stress"   ? OutputKind::STRESS
                                              : throw Error(std::string(call) + ": unknown kind \"" + kind +
                                                            "\" (spheres, clumps, contacts, meshes, stress)");
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
