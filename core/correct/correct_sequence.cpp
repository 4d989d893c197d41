// The sequence: each frame corrected alone (reusing what an earlier run kept), then every frame's
// correction replaced by a Gaussian blend in time of its neighbours' and its own, checked frame by
// frame: where the blend would add intersecting faces, the frame's own correction comes back in
// quarters until it does not.
#include "correct/stretch_measure.hpp"

#include <posekit/correct_sequence.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/self_intersections.hpp>

#include <tbb/parallel_for.h>

#include <mutex>
#include <optional>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace posekit {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void check_input(const Eigen::Ref<const Eigen::MatrixX3d>& reference, const std::vector<Eigen::MatrixX3d>& frames,
                 const SequenceCorrectionOptions& options, const std::vector<Eigen::MatrixX3d>* earlier) {
  if (frames.empty()) throw ArgumentError("the sequence has no frame");
  if (!std::isfinite(options.smoothing_frames) || options.smoothing_frames < 0.0) {
    throw ArgumentError("smoothing_frames must be finite and >= 0, got " + std::to_string(options.smoothing_frames));
  }
  for (size_t t = 0; t < frames.size(); ++t) {
    if (frames[t].rows() != reference.rows()) {
      throw ArgumentError("frame " + std::to_string(t) + " has " + std::to_string(frames[t].rows()) +
                          " vertices but the reference has " + std::to_string(reference.rows()));
    }
    if (!frames[t].allFinite()) throw ArgumentError("frame " + std::to_string(t) + " has a coordinate that is not finite");
  }
  if (earlier == nullptr) return;
  if (earlier->size() != frames.size()) {
    throw ArgumentError(std::to_string(earlier->size()) + " earlier corrections for " + std::to_string(frames.size()) +
                        " frames");
  }
  for (size_t t = 0; t < frames.size(); ++t) {
    const Eigen::MatrixX3d& kept = (*earlier)[t];
    if (kept.size() != 0 && (kept.rows() != reference.rows() || !kept.allFinite())) {
      throw ArgumentError("the earlier correction of frame " + std::to_string(t) + " does not fit the reference");
    }
  }
}

int new_face_count(const Eigen::Ref<const Eigen::MatrixX3d>& pose, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                   const std::vector<int>& reference_faces) {
  return static_cast<int>(new_intersecting_faces(self_intersecting_faces(pose, faces), reference_faces).size());
}

// Gaussian weights of frames t - radius ... t + radius.
std::vector<double> gaussian_weights(double sigma) {
  if (sigma <= 0.0) return {1.0};
  const int radius = blend_radius(sigma);
  std::vector<double> weights(static_cast<size_t>(2 * radius + 1));
  for (int k = -radius; k <= radius; ++k) {
    weights[static_cast<size_t>(k + radius)] = std::exp(-0.5 * (k * k) / (sigma * sigma));
  }
  return weights;
}

// Largest per-vertex change of `offsets` between consecutive usable frames.
double largest_offset_change(const std::vector<Eigen::MatrixX3d>& offsets, const std::vector<char>& usable) {
  double largest = 0.0;
  for (size_t t = 1; t < offsets.size(); ++t) {
    if (!usable[t] || !usable[t - 1]) continue;
    largest = std::max(largest, (offsets[t] - offsets[t - 1]).rowwise().norm().maxCoeff());
  }
  return largest;
}

struct Acceleration {
  double p99 = 0;
  double max = 0;
};

// 99th percentile and maximum of |x(t+1) - 2 x(t) + x(t-1)| over `vertices` and the interior frames
// whose three poses are usable.
Acceleration acceleration(const std::vector<const Eigen::MatrixX3d*>& poses, const std::vector<int>& vertices,
                          const std::vector<char>& usable) {
  std::vector<double> values;
  for (size_t t = 1; t + 1 < poses.size(); ++t) {
    if (!usable[t - 1] || !usable[t] || !usable[t + 1]) continue;
    for (const int v : vertices) {
      values.push_back((poses[t + 1]->row(v) - 2.0 * poses[t]->row(v) + poses[t - 1]->row(v)).norm());
    }
  }
  if (values.empty()) return {};
  const auto rank = static_cast<std::ptrdiff_t>(std::floor(0.99 * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  Acceleration out;
  out.p99 = values[static_cast<size_t>(rank)];
  out.max = *std::max_element(values.begin(), values.end());
  return out;
}

// Frame t with the smallest quarter of the previous frame's correction that frees it without stretching
// more faces than the previous result has (frame.carried and frame.carried_scale set), or nullopt.
std::optional<Eigen::MatrixX3d> carry_previous(int t, const std::vector<Eigen::MatrixX3d>& frames,
                                               const std::vector<Eigen::MatrixX3d>& own, const std::vector<char>& usable,
                                               const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                               const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                               const std::vector<int>& reference_faces, FrameCorrection& frame) {
  const auto previous = static_cast<size_t>(t - 1);
  if (!usable[previous]) return std::nullopt;
  const Eigen::MatrixX3d offset = own[previous] - frames[previous];
  if (!(offset.array() != 0.0).any()) return std::nullopt;
  const detail::StretchMeasure previous_stretch(reference, frames[previous], faces);
  const int allowed_stretch = previous_stretch.count(own[previous]);
  const detail::StretchMeasure stretch(reference, frames[static_cast<size_t>(t)], faces);
  for (int quarter = 1; quarter <= 4; ++quarter) {
    Eigen::MatrixX3d pose = frames[static_cast<size_t>(t)] + 0.25 * quarter * offset;
    if (new_face_count(pose, faces, reference_faces) == 0 && stretch.count(pose) <= allowed_stretch) {
      frame.carried = true;
      frame.carried_scale = 0.25 * quarter;
      return pose;
    }
  }
  return std::nullopt;
}

double ratio(double value, double base) { return base > 0.0 ? value / base : (value > 0.0 ? INFINITY : 1.0); }

}  // namespace

int blend_radius(double smoothing_frames) {
  return smoothing_frames > 0.0 ? static_cast<int>(std::ceil(3.0 * smoothing_frames)) : 0;
}

std::vector<FrameCorrection> correct_sequence(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                              const std::vector<Eigen::MatrixX3d>& frames,
                                              const Eigen::Ref<const Eigen::MatrixX3i>& faces, Device& device,
                                              const SequenceCorrectionOptions& options, SequenceReport* report,
                                              const SequenceCallbacks& callbacks,
                                              const std::vector<Eigen::MatrixX3d>* earlier) {
  const Clock::time_point start = Clock::now();
  check_input(reference, frames, options, earlier);
  const int frame_count = static_cast<int>(frames.size());
  const std::vector<int> reference_faces = self_intersecting_faces(reference, faces);
  std::vector<FrameCorrection> out(frames.size());
  std::vector<Eigen::MatrixX3d> own(frames.size());
  std::vector<char> usable(frames.size(), 1);  // not vector<bool>: runs write their frames' entries concurrently

  // Which frames need a correction, every frame at once.
  tbb::parallel_for(0, frame_count, [&](int t) {
    out[static_cast<size_t>(t)].target_new_faces = new_face_count(frames[static_cast<size_t>(t)], faces, reference_faces);
  });
  // A correction is carried only from frame to frame within a run of frames that need one, so the runs
  // are independent of each other and are corrected in parallel.
  std::vector<std::pair<int, int>> runs;  // [first, last)
  int done = 0;
  for (int t = 0; t < frame_count; ++t) {
    if (out[static_cast<size_t>(t)].target_new_faces == 0) {
      own[static_cast<size_t>(t)] = frames[static_cast<size_t>(t)];
      ++done;
    } else if (!runs.empty() && runs.back().second == t) {
      ++runs.back().second;
    } else {
      runs.emplace_back(t, t + 1);
    }
  }
  std::mutex callback_mutex;
  if (callbacks.progress && done > 0) callbacks.progress(done, frame_count);
  const auto correct_frame = [&](int t) {
    const auto index = static_cast<size_t>(t);
    FrameCorrection& frame = out[index];
    if (earlier != nullptr && (*earlier)[index].size() != 0) {
      own[index] = (*earlier)[index];
      frame.corrected = true;
      frame.reused = true;
      return;
    }
    const Clock::time_point frame_start = Clock::now();
    std::optional<Eigen::MatrixX3d> carried;
    if (options.carry_corrections && t > 0) {
      carried = carry_previous(t, frames, own, usable, faces, reference, reference_faces, frame);
    }
    if (carried) {
      own[index] = std::move(*carried);
      frame.corrected = true;
    } else {
      try {
        own[index] = correct_pose(reference, frames[index], faces, device, options.frame, &frame.report);
        frame.corrected = true;
      } catch (const DeviceError&) {
        throw;
      } catch (const Error& error) {
        frame.error = error.what();
        usable[index] = 0;
      }
    }
    frame.seconds = seconds_since(frame_start);
  };
  tbb::parallel_for(0, static_cast<int>(runs.size()), 1, [&](int r) {
    for (int t = runs[static_cast<size_t>(r)].first; t < runs[static_cast<size_t>(r)].second; ++t) {
      correct_frame(t);
      const std::lock_guard<std::mutex> lock(callback_mutex);
      const auto index = static_cast<size_t>(t);
      if (usable[index] != 0 && !out[index].reused && callbacks.frame_corrected) callbacks.frame_corrected(t, own[index]);
      ++done;
      if (callbacks.progress) callbacks.progress(done, frame_count);
    }
  });
  const double correction_seconds = seconds_since(start);

  // The blend in time.
  const Clock::time_point blend_start = Clock::now();
  std::vector<Eigen::MatrixX3d> offsets(frames.size());
  std::vector<bool> moved(frames.size(), false);
  for (size_t t = 0; t < frames.size(); ++t) {
    offsets[t] = usable[t] ? Eigen::MatrixX3d(own[t] - frames[t]) : Eigen::MatrixX3d::Zero(reference.rows(), 3);
    moved[t] = usable[t] && (offsets[t].array() != 0.0).any();
  }
  const std::vector<double> weights = gaussian_weights(options.smoothing_frames);
  const int radius = static_cast<int>(weights.size() / 2);
  tbb::parallel_for(0, frame_count, [&](int t) {
    const auto index = static_cast<size_t>(t);
    FrameCorrection& frame = out[index];
    if (!usable[index]) return;
    Eigen::MatrixX3d blended = Eigen::MatrixX3d::Zero(reference.rows(), 3);
    double total = 0.0;
    bool any = false;
    for (int u = std::max(0, t - radius); u <= std::min(frame_count - 1, t + radius); ++u) {
      if (!usable[static_cast<size_t>(u)]) continue;
      const double w = weights[static_cast<size_t>(u - t + radius)];
      total += w;
      if (!moved[static_cast<size_t>(u)]) continue;
      blended += w * offsets[static_cast<size_t>(u)];
      any = true;
    }
    if (!any) {
      frame.vertices = frames[index];
      return;
    }
    if (weights.size() == 1) {
      // No blend: the frame's own correction exactly (target + (own - target) may round differently).
      frame.vertices = own[index];
      frame.own_share = 1.0;
      frame.new_faces = frame.corrected ? new_face_count(own[index], faces, reference_faces) : 0;
      return;
    }
    blended /= total;
    const int allowed = frame.corrected ? new_face_count(own[index], faces, reference_faces) : 0;
    // Quarters of the frame's own correction back until the blend adds no intersecting face.
    for (int quarter = 0; quarter <= 4; ++quarter) {
      const double share = 0.25 * quarter;
      Eigen::MatrixX3d pose = frames[index] + blended + share * (offsets[index] - blended);
      const int count = quarter == 4 ? allowed : new_face_count(pose, faces, reference_faces);
      if (count <= allowed) {
        frame.vertices = std::move(pose);
        frame.own_share = share;
        frame.new_faces = count;
        break;
      }
    }
  });
  for (size_t t = 0; t < frames.size(); ++t) {
    if (!usable[t]) continue;
    FrameCorrection& frame = out[t];
    frame.touched = (frame.vertices.array() != frames[t].array()).any();
    Eigen::VectorXd distances = (frame.vertices - frames[t]).rowwise().norm();
    frame.max_distance_to_target = distances.maxCoeff();
    const auto middle = distances.size() / 2;
    std::nth_element(distances.data(), distances.data() + middle, distances.data() + distances.size());
    frame.median_distance_to_target = distances(middle);
    frame.stretched_faces = detail::StretchMeasure(reference, frames[t], faces).count(frame.vertices);
  }

  if (report != nullptr) {
    SequenceReport& r = *report;
    r = SequenceReport{};
    r.frames = frame_count;
    r.bounding_box_diagonal = bounding_box_diagonal(reference);
    for (const FrameCorrection& frame : out) {
      r.corrected_frames += frame.corrected ? 1 : 0;
      r.carried_frames += frame.carried ? 1 : 0;
      r.touched_frames += frame.touched ? 1 : 0;
      r.failed_frames += frame.error.empty() ? 0 : 1;
      r.frames_with_new_faces += frame.new_faces > 0 ? 1 : 0;
    }
    // Vertices moved in some frame, by their own correction or by the blend.
    std::vector<int> vertices;
    std::vector<Eigen::MatrixX3d> final_offsets(frames.size(), Eigen::MatrixX3d::Zero(reference.rows(), 3));
    for (size_t t = 0; t < frames.size(); ++t) {
      if (usable[t]) final_offsets[t] = out[t].vertices - frames[t];
    }
    for (Eigen::Index v = 0; v < reference.rows(); ++v) {
      for (size_t t = 0; t < frames.size(); ++t) {
        if (!usable[t]) continue;
        if ((final_offsets[t].row(v).array() != 0.0).any() || (offsets[t].row(v).array() != 0.0).any()) {
          vertices.push_back(static_cast<int>(v));
          break;
        }
      }
    }
    SequenceCoherence& c = r.coherence;
    c.vertices = static_cast<int>(vertices.size());
    const double diagonal = std::max(r.bounding_box_diagonal, 1e-300);
    c.largest_offset_change = largest_offset_change(final_offsets, usable) / diagonal;
    c.largest_offset_change_alone = largest_offset_change(offsets, usable) / diagonal;
    std::vector<const Eigen::MatrixX3d*> targets, results, alone;
    for (size_t t = 0; t < frames.size(); ++t) {
      targets.push_back(&frames[t]);
      results.push_back(usable[t] ? &out[t].vertices : &frames[t]);
      alone.push_back(usable[t] ? &own[t] : &frames[t]);
    }
    const Acceleration base = acceleration(targets, vertices, usable);
    const Acceleration blended = acceleration(results, vertices, usable);
    const Acceleration separate = acceleration(alone, vertices, usable);
    c.acceleration_p99_ratio = ratio(blended.p99, base.p99);
    c.acceleration_max_ratio = ratio(blended.max, base.max);
    c.acceleration_p99_ratio_alone = ratio(separate.p99, base.p99);
    c.acceleration_max_ratio_alone = ratio(separate.max, base.max);
    r.correction_seconds = correction_seconds;
    r.coherence_seconds = seconds_since(blend_start);
    r.seconds = seconds_since(start);
  }
  return out;
}

}  // namespace posekit
