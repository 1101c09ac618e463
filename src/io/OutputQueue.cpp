#include "io/OutputQueue.h"

#include <exception>
#include <iostream>

#include <deme/Error.h>

namespace deme {

OutputQueue::~OutputQueue() {
    {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_cv.wait(lock, [this] { return !m_busy; });
        m_stop = true;
    }
    m_cv.notify_all();
    if (m_thread.joinable()) m_thread.join();
    // A destructor cannot throw: a failure no later call collected is said, not lost.
    if (!m_error.empty()) std::cerr << "[deme] error: " << m_error << std::endl;
}

void OutputQueue::wait(const std::string& collectingCall) {
    std::string error;
    {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_cv.wait(lock, [this] { return !m_busy; });
        error.swap(m_error);
    }
    if (!error.empty()) throw Error(error + " [written in the background; reported by " + collectingCall + "]");
}

bool OutputQueue::busy() {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_busy;
}

void OutputQueue::submit(std::function<void()> job) {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_job = std::move(job);
        m_busy = true;
        if (!m_thread.joinable()) m_thread = std::thread(&OutputQueue::run, this);
    }
    m_cv.notify_all();
}

void OutputQueue::run() {
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_cv.wait(lock, [this] { return m_stop || m_job; });
        if (!m_job) return;  // stopping, nothing left to do
        std::function<void()> job = std::move(m_job);
        m_job = nullptr;
        lock.unlock();
        std::string error;
        try {
            job();
        } catch (const std::exception& e) {
            error = e.what();
        } catch (...) {
            error = "unknown failure while writing output";
        }
        job = nullptr;  // the staged frame goes before the caller may stage the next one
        lock.lock();
        m_error = error;
        m_busy = false;
        m_cv.notify_all();
    }
}

}  // namespace deme
