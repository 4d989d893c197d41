#include <climits>
#include <string>
#include <utility>

#include "posekit/error.hpp"
#include "posekit/mesh.hpp"

namespace posekit {

void PoseSet::add_pose(Eigen::MatrixX3d vertices, std::string name) {
  const Eigen::Index rows = vertices.rows();
  const std::string label = name.empty() ? "" : " '" + name + "'";
  if (!poses_.empty() && rows != poses_.front().rows()) {
    throw ArgumentError("PoseSet::add_pose: vertices of pose" + label + " has " + std::to_string(rows) +
                        " rows, but the poses of this set have " + std::to_string(poses_.front().rows()));
  }
  if (rows > INT_MAX) {
    throw ArgumentError("PoseSet::add_pose: vertices of pose" + label + " has more than " + std::to_string(INT_MAX) +
                        " rows");
  }
  // The first pose fixes the vertex count; the shared faces must stay inside it.
  if (poses_.empty() && faces_.size() > 0 && (faces_.minCoeff() < 0 || faces_.maxCoeff() >= rows)) {
    throw ArgumentError("PoseSet::add_pose: vertices of pose" + label + " has " + std::to_string(rows) +
                        " rows, but the faces use vertex indices from " + std::to_string(faces_.minCoeff()) + " to " +
                        std::to_string(faces_.maxCoeff()));
  }
  poses_.push_back(std::move(vertices));
  names_.push_back(std::move(name));
}

}  // namespace posekit
