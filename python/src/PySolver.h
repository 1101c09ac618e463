// The Python face of DEMSolver: the C++ solver plus what Python needs around a long run. Calls that
// step (DoDynamics, DoDynamicsThenSync, DoStepDynamics) release the GIL while they run, and poll
// Ctrl-C through the solver's interrupt check: every 50 ms at most, between steps, the check takes
// the GIL back and runs Python's signal handlers. A KeyboardInterrupt (or an exception from the
// user's own check) stops the call at a step boundary, with the state consistent, and is raised
// from the call once the C++ side returned; the next call goes on from where it stopped.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <deme/DEMSolver.h>

#include "Casters.h"

namespace deme_py {

class PySolver : public deme::DEMSolver {
  public:
    PySolver() = default;
    explicit PySolver(unsigned int nGPUs) : deme::DEMSolver(nGPUs) {}
    explicit PySolver(const std::vector<int>& ids) : deme::DEMSolver(ids) {}

    // A Python callable polled with the signal check (None removes it); true stops the call.
    void setUserInterruptCheck(py::object check) { m_userCheck = std::move(check); }

    // Runs body() with the GIL released and Ctrl-C polled; then raises what the check caught.
    template <class Body>
    void runInterruptible(Body&& body) {
        std::shared_ptr<py::error_already_set> caught;
        py::object user = m_userCheck;
        SetInterruptCheck([&caught, &user]() -> bool {
            py::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {
                caught = std::make_shared<py::error_already_set>();
                return true;
            }
            if (user.is_none()) return false;
            try {
                const py::object stop = user();
                const int truth = PyObject_IsTrue(stop.ptr());
                if (truth < 0) throw py::error_already_set();
                return truth == 1;
            } catch (py::error_already_set& e) {
                caught = std::make_shared<py::error_already_set>(std::move(e));
                return true;
            }
        });
        try {
            py::gil_scoped_release release;
            body();
        } catch (...) {
            SetInterruptCheck(nullptr);
            throw;
        }
        SetInterruptCheck(nullptr);
        if (caught) throw *caught;
    }

    // Long calls that never call back into Python (Initialize may compile a force model).
    template <class Body>
    void runWithoutGil(Body&& body) {
        py::gil_scoped_release release;
        body();
    }

    template <class Body>
    void runWithoutGilConst(Body&& body) const {
        py::gil_scoped_release release;
        body();
    }

  private:
    py::object m_userCheck = py::none();
};

}  // namespace deme_py
