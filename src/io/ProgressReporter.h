// The progress line of long DoDynamics calls and the summary at their end, fed by the run monitor's
// polls (RunProgress, whose wallSeconds is the reporter's clock). Silent below INFO verbosity, when
// turned off, and for calls shorter than the interval: the first line comes once a call has run
// `interval` seconds of wall time, the next no sooner than `interval` after it. On a terminal one
// line is redrawn ('\r'); elsewhere (a log file, a pipe) each report is a line of its own.
#pragma once

#include <functional>
#include <ostream>
#include <string>

#include <deme/RunProgress.h>
#include <deme/RunSummary.h>

#include "runtime/Settings.h"

namespace deme {

class ProgressReporter {
  public:
    ProgressReporter(std::ostream& out, bool redraw) : m_out(out), m_redraw(redraw) {}
    void setEnabled(bool on) { m_enabled = on; }
    void setInterval(double seconds) { m_interval = seconds; }
    // One poll of the monitor. `summary` is asked for the end-of-call figures only when they are printed.
    void onProgress(const RunProgress& p, Verbosity level, const std::function<RunSummary()>& summary);

    // "[deme] t = 0.5 of 2 s (25.0 %), 4.12e+06 sphere-steps/s, ETA 1 min 05 s"
    static std::string progressLine(const RunProgress& p);
    // "[deme] run: 0.2 s simulated in 12.3 s wall, 40000 steps, 4.97e+06 sphere-steps/s, 4.67 contacts/sphere, ..."
    static std::string summaryLine(const RunSummary& s, bool stoppedEarly);

  private:
    std::ostream& m_out;
    bool m_redraw;
    bool m_enabled = true;
    double m_interval = 5.0;
    bool m_inCall = false, m_printed = false;
    double m_lastLine = 0.0;
    size_t m_lastLength = 0;
};

// Peak resident memory of this process so far (getrusage), in bytes.
size_t peakHostResidentBytes();

}  // namespace deme
