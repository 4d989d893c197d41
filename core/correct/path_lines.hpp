// The path lines of a correction: where each vertex was at any time of the motion. Vertices in a
// field's region moved through that field; every other vertex followed its key-frame trajectory,
// which the fields reproduce there up to their fitting error anyway.
#pragma once

#include "correct/vertex_trajectories.hpp"

#include <posekit/device.hpp>

#include <Eigen/Core>

#include <memory>
#include <mutex>
#include <vector>

namespace posekit::detail {

/// One fitted field and the weight of time in its domain (t runs from 0 to time_scale).
struct TimedField {
  RbfField field;
  double time_scale = 1.0;
};

class PathLines {
 public:
  PathLines() = default;
  /// `reference` (#V by 3) starts every path; vertex v moves through fields[field_of_vertex[v]], or
  /// along `trajectories` where that is -1. `device` must outlive the object.
  PathLines(const Eigen::Ref<const Eigen::MatrixX3d>& reference, std::shared_ptr<const VertexTrajectories> trajectories,
            std::vector<TimedField> fields, std::vector<int> field_of_vertex, Device& device, Rk45StepControl integration);

  /// Positions of `vertices` at times k / segments of the motion, k = 0 .. segments: element k is
  /// #vertices by 3, in the order given. Each vertex is integrated once per `segments`: the repairs
  /// that move regions back in time ask again for the vertices of overlapping regions.
  std::vector<Eigen::MatrixX3d> sample(const std::vector<int>& vertices, int segments) const;

 private:
  struct Uploaded {
    std::mutex mutex;
    std::vector<std::unique_ptr<DeviceField>> fields;
  };
  /// Every vertex's positions at the times of one `segments`, filled as vertices are asked for.
  struct Sampled {
    int segments = 0;
    std::vector<char> known;                 ///< per vertex
    std::vector<Eigen::MatrixX3d> positions;  ///< per time, #V by 3
  };
  struct SampleCache {
    std::mutex mutex;
    std::vector<Sampled> by_segments;
  };
  std::vector<Eigen::MatrixX3d> integrate(const std::vector<int>& vertices, int segments) const;
  Eigen::MatrixX3d reference_;
  std::shared_ptr<const VertexTrajectories> trajectories_;
  std::vector<TimedField> fields_;
  std::vector<int> field_of_vertex_;
  Device* device_ = nullptr;
  Rk45StepControl integration_;
  std::shared_ptr<Uploaded> uploaded_ = std::make_shared<Uploaded>();
  std::shared_ptr<SampleCache> cache_ = std::make_shared<SampleCache>();
};

}  // namespace posekit::detail
