#include "correct/path_lines.hpp"

#include <algorithm>
#include <utility>

namespace posekit::detail {

PathLines::PathLines(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                     std::shared_ptr<const VertexTrajectories> trajectories,
                     std::vector<TimedField> fields, std::vector<int> field_of_vertex, Device& device,
                     Rk45StepControl integration)
    : reference_(reference),
      trajectories_(std::move(trajectories)),
      fields_(std::move(fields)),
      field_of_vertex_(std::move(field_of_vertex)),
      device_(&device),
      integration_(integration) {}

std::vector<Eigen::MatrixX3d> PathLines::sample(const std::vector<int>& vertices, int segments) const {
  const auto vertex_count = static_cast<size_t>(reference_.rows());
  const auto cached = [&]() -> Sampled* {
    for (Sampled& s : cache_->by_segments) {
      if (s.segments == segments) return &s;
    }
    return nullptr;
  };
  std::vector<int> missing;
  {
    std::lock_guard<std::mutex> lock(cache_->mutex);
    const Sampled* sampled = cached();
    for (int v : vertices) {
      if (sampled == nullptr || sampled->known[static_cast<size_t>(v)] == 0) missing.push_back(v);
    }
  }
  std::sort(missing.begin(), missing.end());
  missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
  // Integrated outside the lock; two callers asking for the same vertex at once compute the same rows.
  const std::vector<Eigen::MatrixX3d> computed = integrate(missing, segments);
  std::lock_guard<std::mutex> lock(cache_->mutex);
  Sampled* sampled = cached();
  if (sampled == nullptr) {
    cache_->by_segments.emplace_back();
    sampled = &cache_->by_segments.back();
    sampled->segments = segments;
    sampled->known.assign(vertex_count, 0);
    sampled->positions.assign(static_cast<size_t>(segments) + 1, Eigen::MatrixX3d(reference_.rows(), 3));
  }
  for (size_t i = 0; i < missing.size(); ++i) {
    for (int k = 0; k <= segments; ++k) {
      sampled->positions[static_cast<size_t>(k)].row(missing[i]) = computed[static_cast<size_t>(k)].row(static_cast<Eigen::Index>(i));
    }
    sampled->known[static_cast<size_t>(missing[i])] = 1;
  }
  std::vector<Eigen::MatrixX3d> samples(static_cast<size_t>(segments) + 1);
  for (int k = 0; k <= segments; ++k) samples[static_cast<size_t>(k)] = sampled->positions[static_cast<size_t>(k)](vertices, Eigen::all);
  return samples;
}

std::vector<Eigen::MatrixX3d> PathLines::integrate(const std::vector<int>& vertices, int segments) const {
  const auto count = static_cast<Eigen::Index>(vertices.size());
  std::vector<Eigen::MatrixX3d> samples(static_cast<size_t>(segments) + 1, Eigen::MatrixX3d(count, 3));
  // Rows of `vertices` by the field they move through; -1 (no field) first.
  std::vector<std::vector<Eigen::Index>> rows_of_field(fields_.size() + 1);
  for (Eigen::Index i = 0; i < count; ++i) {
    const int field = field_of_vertex_.empty() ? -1 : field_of_vertex_[static_cast<size_t>(vertices[static_cast<size_t>(i)])];
    rows_of_field[static_cast<size_t>(field + 1)].push_back(i);
  }
  for (Eigen::Index i : rows_of_field.front()) {
    const int v = vertices[static_cast<size_t>(i)];
    for (int k = 0; k <= segments; ++k) {
      samples[static_cast<size_t>(k)].row(i) =
          k == 0 ? Eigen::RowVector3d(reference_.row(v))
                 : Eigen::RowVector3d(trajectories_->position(v, static_cast<double>(k) / segments).transpose());
    }
  }
  for (size_t f = 0; f < fields_.size(); ++f) {
    const std::vector<Eigen::Index>& rows = rows_of_field[f + 1];
    if (rows.empty()) continue;
    const DeviceField* uploaded = nullptr;
    {
      std::lock_guard<std::mutex> lock(uploaded_->mutex);
      if (uploaded_->fields.size() != fields_.size()) uploaded_->fields.resize(fields_.size());
      if (!uploaded_->fields[f]) uploaded_->fields[f] = device_->upload_field(fields_[f].field);
      uploaded = uploaded_->fields[f].get();
    }
    Eigen::MatrixX3d positions(static_cast<Eigen::Index>(rows.size()), 3);
    for (size_t r = 0; r < rows.size(); ++r) {
      positions.row(static_cast<Eigen::Index>(r)) = reference_.row(vertices[static_cast<size_t>(rows[r])]);
    }
    const auto store = [&](int k) {
      for (size_t r = 0; r < rows.size(); ++r) samples[static_cast<size_t>(k)].row(rows[r]) = positions.row(static_cast<Eigen::Index>(r));
    };
    store(0);
    for (int k = 1; k <= segments; ++k) {
      const Rk45Options segment{integration_, fields_[f].time_scale * (k - 1) / segments,
                                fields_[f].time_scale * k / segments};
      device_->integrate_rk45(*uploaded, positions, segment);
      store(k);
    }
  }
  return samples;
}

}  // namespace posekit::detail
