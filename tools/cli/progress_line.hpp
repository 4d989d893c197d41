// A one-line progress display on stderr, shown only when stderr is a terminal and only for stages
// that have run longer than a second.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace posekit::cli {

class ProgressLine {
 public:
  explicit ProgressLine(std::string task);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// A callback for the library: (stage, fraction done).
  std::function<void(const std::string&, double)> callback();
  /// Clears the line and stops the display.
  void finish();

 private:
  void tick();
  std::string task_;
  bool enabled_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_;
  bool shown_ = false;
  bool stopping_ = false;
  std::thread ticker_;
};

}  // namespace posekit::cli
