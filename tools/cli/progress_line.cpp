#include "progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace posekit::cli {

ProgressLine::ProgressLine(std::string task, bool stage_lines)
    : task_(std::move(task)), terminal_(isatty(STDERR_FILENO) == 1), stage_lines_(stage_lines || terminal_) {
  if (terminal_) ticker_ = std::thread([this] { tick(); });
}

ProgressLine::~ProgressLine() { finish(); }

std::function<void(const std::string&, double)> ProgressLine::callback() {
  return [this](const std::string& stage, double fraction) {
    if (!terminal_ && !stage_lines_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    if (fraction <= 0.0) {
      stage_ = stage;
      stage_start_ = now;
      started_.emplace(stage, now);
      return;
    }
    if (fraction < 1.0) return;
    const auto found = started_.find(stage);
    if (stage_lines_ && found != started_.end()) {
      const double seconds = std::chrono::duration<double>(now - found->second).count();
      std::fprintf(stderr, "%s%s: %s (%.2f s)\n", terminal_ ? "\r\033[K" : "", task_.c_str(), stage.c_str(), seconds);
      std::fflush(stderr);
      shown_ = false;
    }
    if (found != started_.end()) started_.erase(found);
    if (stage == stage_) stage_.clear();
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
