#include "frame_progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace posekit::cli {

std::string duration_text(double seconds) {
  const long total = std::lround(std::max(seconds, 0.0));
  char text[48];
  if (total >= 3600) {
    std::snprintf(text, sizeof text, "%ld h %02ld min", total / 3600, (total % 3600) / 60);
  } else if (total >= 60) {
    std::snprintf(text, sizeof text, "%ld min %02ld s", total / 60, total % 60);
  } else {
    std::snprintf(text, sizeof text, "%ld s", total);
  }
  return text;
}

FrameProgress::FrameProgress(std::string task, bool lines)
    : task_(std::move(task)), terminal_(isatty(STDERR_FILENO) == 1), lines_(lines), start_(std::chrono::steady_clock::now()) {}

void FrameProgress::update(int done, int total, int skipped) {
  if (!terminal_ && !lines_) return;
  const int tenth = total > 0 ? (10 * done) / total : 10;
  if (!terminal_ && tenth == last_tenth_) return;
  last_tenth_ = tenth;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int worked = done - skipped;
  std::string left = "estimating the time left";
  if (worked > 0) left = "about " + duration_text(elapsed / worked * (total - done)) + " left";
  if (done == total) left = duration_text(elapsed) + " in all";
  constexpr int width = 30;
  const int filled = total > 0 ? (width * done) / total : width;
  const std::string bar = std::string(static_cast<size_t>(filled), '#') + std::string(static_cast<size_t>(width - filled), '.');
  std::fprintf(stderr, "%s%s: [%s] %d/%d frames, %s%s", terminal_ ? "\r\033[K" : "", task_.c_str(), bar.c_str(), done,
               total, left.c_str(), terminal_ ? "" : "\n");
  std::fflush(stderr);
  drawn_ = terminal_;
}

void FrameProgress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\n");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace posekit::cli
