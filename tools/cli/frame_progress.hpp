// A progress bar for a run over many frames, on stderr: frames done out of all and an estimate of
// the time left from the mean time per frame so far. Redrawn in place on a terminal; elsewhere, when
// asked for, one line per tenth of the run.
#pragma once

#include <chrono>
#include <string>

namespace posekit::cli {

class FrameProgress {
 public:
  /// `task` prefixes the line; `lines` asks for the lines also when stderr is not a terminal.
  FrameProgress(std::string task, bool lines);
  /// `done` of `total` frames are finished; `skipped` of them cost nothing (reused from an earlier run).
  void update(int done, int total, int skipped = 0);
  /// Ends the line.
  void finish();

 private:
  std::string task_;
  bool terminal_;
  bool lines_;
  int last_tenth_ = -1;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

/// "1 h 02 min", "3 min 20 s", "45 s".
std::string duration_text(double seconds);

}  // namespace posekit::cli
