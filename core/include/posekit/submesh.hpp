// Parts of a mesh: the faces a caller keeps, with only the vertices they use.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// The faces f of `faces` with keep_face[f] set (one flag per face), and only the vertices they use,
/// renumbered in order of first use; `original_vertex`, when given, receives the vertex of
/// `vertices` behind each vertex of the result (a partial scan, a region to work on alone).
Mesh submesh(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
             const std::vector<char>& keep_face,
             std::vector<int>* original_vertex = nullptr);

}  // namespace posekit
