// A second thread for `cdlab figures` and `cdlab render`: scene i's PNG encoding and file writes
// run while the GL thread draws scene i + 1 (encoding is CPU work that nothing overlapped before).
// Tasks run one at a time in submission order; at most `depth` wait, so the images held in memory
// stay bounded. Each task returns its report; finish() hands them back in submission order.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace cdlab::demos {

/// What one scene's write produced: its error line (empty on success), the frames written and the
/// line `cdlab render` prints for it.
struct WriteReport {
    std::string error;
    int frames = 0;
    std::string note;
};

class BackgroundWriter {
public:
    /// threaded = false: submit() runs the task at once on the caller's thread (profiling: the
    /// phases are timed one after the other).
    BackgroundWriter(bool threaded, int depth = 2);
    ~BackgroundWriter();
    BackgroundWriter(const BackgroundWriter&) = delete;
    BackgroundWriter& operator=(const BackgroundWriter&) = delete;

    /// Queues a task (blocks while `depth` tasks wait). The task must not throw.
    void submit(std::function<WriteReport()> task);
    /// Waits for every task; the reports of all tasks since the last finish(), in order.
    std::vector<WriteReport> finish();

private:
    void work();

    const bool threaded_;
    const int depth_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<std::function<WriteReport()>> queue_;
    std::vector<WriteReport> reports_;
    bool busy_ = false, stopping_ = false;
    std::thread worker_;
};

}  // namespace cdlab::demos
