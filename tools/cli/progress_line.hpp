// Progress on stderr: on a terminal, a transient line naming the step under way once it has run
// longer than a second; and, on a terminal or when asked for, one lasting line per finished stage
// with its wall time.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace posekit::cli {

class ProgressLine {
 public:
  /// `task` prefixes every line; `stage_lines` asks for the lasting lines also when stderr is not a
  /// terminal.
  explicit ProgressLine(std::string task, bool stage_lines = false);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// A callback for the library: (stage, fraction done); a stage that reports 1 gets its line.
  std::function<void(const std::string&, double)> callback();
  /// Clears the transient line and stops the display.
  void finish();

 private:
  void tick();
  std::string task_;
  bool terminal_;
  bool stage_lines_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_;
  std::map<std::string, std::chrono::steady_clock::time_point> started_;
  bool shown_ = false;
  bool stopping_ = false;
  std::thread ticker_;
};

}  // namespace posekit::cli
