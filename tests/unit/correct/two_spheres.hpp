// Two unit spheres in one mesh, for the tests of stages that part bodies pressed into each other.
#pragma once

#include "icosphere.hpp"

#include <posekit/mesh.hpp>

namespace posekit::testing {

/// Two level-3 icospheres (642 vertices each) whose centers lie `distance` apart along x.
inline Mesh two_spheres(double distance) {
  const Mesh sphere = icosphere(3);
  const Eigen::Index n = sphere.vertices.rows();
  Mesh both;
  both.vertices.resize(2 * n, 3);
  both.faces.resize(2 * sphere.faces.rows(), 3);
  both.vertices.topRows(n) = sphere.vertices.rowwise() - Eigen::RowVector3d(distance / 2, 0, 0);
  both.vertices.bottomRows(n) = sphere.vertices.rowwise() + Eigen::RowVector3d(distance / 2, 0, 0);
  both.faces.topRows(sphere.faces.rows()) = sphere.faces;
  both.faces.bottomRows(sphere.faces.rows()) = sphere.faces.array() + static_cast<int>(n);
  return both;
}

}  // namespace posekit::testing
