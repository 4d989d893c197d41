#include "progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace posekit::cli {

ProgressLine::ProgressLine(std::string task) : task_(std::move(task)), enabled_(isatty(STDERR_FILENO) == 1) {
  if (enabled_) ticker_ = std::thread([this] { tick(); });
}

ProgressLine::~ProgressLine() { finish(); }

std::function<void(const std::string&, double)> ProgressLine::callback() {
  return [this](const std::string& stage, double fraction) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (fraction <= 0.0) {
      stage_ = stage;
      stage_start_ = std::chrono::steady_clock::now();
    } else if (fraction >= 1.0 && stage == stage_) {
      stage_.clear();
    }
  };
}

void ProgressLine::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, std::chrono::milliseconds(250));
    if (stopping_) break;
    if (stage_.empty()) continue;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
    if (elapsed < 1.0) continue;
    std::fprintf(stderr, "\r\033[K%s: %s (%.0f s)", task_.c_str(), stage_.c_str(), elapsed);
    std::fflush(stderr);
    shown_ = true;
  }
  if (shown_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
}

void ProgressLine::finish() {
  if (!ticker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  ticker_.join();
}

}  // namespace posekit::cli
