// The writer thread: runs one output job at a time (encoding and writing a staged frame) while the
// caller goes on stepping. A job's failure is kept and thrown as deme::Error by the next wait(),
// which every output call and FlushOutput make before anything else; so an error surfaces at the
// next output call at the latest, and never passes unseen (the destructor prints one no call
// collected).
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace deme {

class OutputQueue {
  public:
    OutputQueue() = default;
    ~OutputQueue();
    OutputQueue(const OutputQueue&) = delete;
    OutputQueue& operator=(const OutputQueue&) = delete;

    // Waits until no job runs; then throws the failure of the last job, if it failed, as a
    // deme::Error whose message is the job's own and says which call collected it.
    void wait(const std::string& collectingCall);
    // Hands a job to the writer thread (started on first use). Call wait() first: one job at a time.
    void submit(std::function<void()> job);
    bool busy();

  private:
    void run();
    std::mutex m_mutex;
    std::condition_variable m_cv;
    std::function<void()> m_job;
    bool m_busy = false, m_stop = false;
    std::string m_error;
    std::thread m_thread;
};

}  // namespace deme
