#include "app/harness/background_writer.h"

#include <utility>

namespace cdlab::demos {

BackgroundWriter::BackgroundWriter(bool threaded, int depth) : threaded_(threaded), depth_(depth < 1 ? 1 : depth) {
    if (threaded_) worker_ = std::thread([this] { work(); });
}

BackgroundWriter::~BackgroundWriter() {
    if (!threaded_) return;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    worker_.join();  // runs what is queued first: no scene is left half-written
}

void BackgroundWriter::submit(std::function<WriteReport()> task) {
    if (!threaded_) {
        reports_.push_back(task());
        return;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return static_cast<int>(queue_.size()) < depth_; });
    queue_.push_back(std::move(task));
    changed_.notify_all();
}

std::vector<WriteReport> BackgroundWriter::finish() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return queue_.empty() && !busy_; });
    return std::exchange(reports_, {});
}

void BackgroundWriter::work() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
        changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
        if (queue_.empty()) return;  // stopping, nothing left
        std::function<WriteReport()> task = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        changed_.notify_all();  // room in the queue
        lock.unlock();
        WriteReport report = task();
        lock.lock();
        reports_.push_back(std::move(report));
        busy_ = false;
        changed_.notify_all();
    }
}

}  // namespace cdlab::demos
