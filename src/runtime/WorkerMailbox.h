// The mailbox between the dynamics thread (dT) and a kinematics worker thread (kT, paper §2.1), for
// the CPU's worker and the GPU's alike: one order at a time goes in, one result comes out, a failure
// of the worker is kept and rethrown to dT once (as a deme::Error naming dT's call and the worker).
//
// Ownership: dT writes an order only while the mailbox is idle (nothing queued, running or waiting
// to be taken); kT owns the order from waitForOrder() until it delivers; dT owns a result from the
// moment it takes it.
#pragma once

#include <condition_variable>
#include <exception>
#include <mutex>
#include <string>
#include <utility>

#include <deme/Error.h>

#include "runtime/WorkerFailure.h"

namespace deme {

template <class Order, class Result>
class WorkerMailbox {
  public:
    // `worker` names kT in messages ("the kinematics thread").
    explicit WorkerMailbox(std::string worker) : m_worker(std::move(worker)) {}

    // ---- dT's side
    // True when no order is queued or running and no result is waiting.
    bool idle() const {
        std::lock_guard<std::mutex> lock(m_mutex);
        return !m_queued && !m_running && !m_ready;
    }
    // Hands kT an order (swapped in, so large buffers move without copies). Only when idle().
    void post(Order& order) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            if (m_queued || m_running || m_ready)
                throwError("DoDynamics", "internal: an order was sent to " + m_worker + " while another was in flight");
            std::swap(m_order, order);
            m_queued = true;
        }
        m_wake.notify_all();
    }
    // Swaps a finished result into `out` (false if none is ready). Rethrows a failure of kT.
    bool tryTake(Result& out) {
        std::lock_guard<std::mutex> lock(m_mutex);
        rethrowWorkerFailure(m_failure, "DoDynamics", m_worker);
        if (!m_ready) return false;
        std::swap(out, m_result);
        m_ready = false;
        return true;
    }
    // Blocks until the order in flight has finished, then swaps its result into `out`.
    void waitAndTake(Result& out) {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_wake.wait(lock, [this] { return m_ready || m_failure || (!m_queued && !m_running); });
        rethrowWorkerFailure(m_failure, "DoDynamics", m_worker);
        if (!m_ready) throwError("DoDynamics", "internal: waited for a result " + m_worker + " was never ordered");
        std::swap(out, m_result);
        m_ready = false;
    }
    // Makes waitForOrder return false (before the owner joins kT).
    void stop() {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_stop = true;
        }
        m_wake.notify_all();
    }

    // ---- kT's side
    // Blocks until an order arrives (swapped into `order`, kT's until it delivers) or stop().
    bool waitForOrder(Order& order) {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_wake.wait(lock, [this] { return m_stop || m_queued; });
        if (m_stop) return false;
        std::swap(order, m_order);
        m_queued = false;
        m_running = true;
        return true;
    }
    // The order's result (swapped out of `result`), or what kT threw instead.
    void deliver(Result& result) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_running = false;
            std::swap(m_result, result);
            m_ready = true;
        }
        m_wake.notify_all();
    }
    void fail(std::exception_ptr failure) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_running = false;
            m_failure = failure;
        }
        m_wake.notify_all();
    }

  private:
    const std::string m_worker;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake;  // kT waits for orders, dT for results
    bool m_stop = false, m_queued = false, m_running = false, m_ready = false;
    std::exception_ptr m_failure;
    Order m_order;
    Result m_result;
};

}  // namespace deme
