// stall_watch.cpp — the run's stall reports (stall_watch.hpp).
#include "stall_watch.hpp"

#include <utility>

namespace shadowref::conform {

StallWatch::StallWatch(Report report, std::chrono::milliseconds after)
    : report_(std::move(report)), after_(after), since_(std::chrono::steady_clock::now()) {
  if (report_) thread_ = std::thread([this] { watch(); });
}

StallWatch::~StallWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void StallWatch::step(std::string what) {
  std::lock_guard<std::mutex> lock(mutex_);
  what_ = std::move(what);
  since_ = std::chrono::steady_clock::now();
  wake_.notify_all();
}

void StallWatch::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    // The next report of this step: `after` past its start, then every `after`.
    const auto started = since_;
    auto due = started + after_;
    while (!stop_ && since_ == started) {
      if (wake_.wait_until(lock, due) == std::cv_status::timeout && since_ == started && !stop_) {
        const auto s = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - started).count();
        const std::string line = "still " + what_ + " after " + std::to_string(s) + " s";
        lock.unlock();
        report_(line);
        lock.lock();
        due += after_;
      }
    }
  }
}

}  // namespace shadowref::conform
