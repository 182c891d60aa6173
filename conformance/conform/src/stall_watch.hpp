// stall_watch.hpp — a line when one step of a run (a reference, a render, a judgement) has gone on
// far longer than any step of a quiet run, repeated while it lasts.
//
// Why: a run that hangs (a driver that never returns, an endless loop of ours) would otherwise end
// mute at its caller's timeout — CTest kills it and a CI log shows nothing but the time. With the
// watch it says which case and which phase it stood in, so the log a CI keeps is evidence. The
// slowest step of the default run takes under 2 s; the large level's reference takes minutes, so a
// report after two minutes is either that (and then it is progress worth a line) or a stall.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace shadowref::conform {

class StallWatch {
 public:
  using Report = std::function<void(const std::string&)>;
  // `report` is called from the watch's own thread ("still <step> after <n> s"), every `after`
  // that one step lasts. An empty `report` watches nothing.
  StallWatch(Report report, std::chrono::milliseconds after);
  ~StallWatch();
  StallWatch(const StallWatch&) = delete;
  StallWatch& operator=(const StallWatch&) = delete;

  // A new step starts now ("drawing sun_horizon x pcss").
  void step(std::string what);

 private:
  void watch();
  Report report_;
  std::chrono::milliseconds after_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string what_;
  std::chrono::steady_clock::time_point since_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace shadowref::conform
