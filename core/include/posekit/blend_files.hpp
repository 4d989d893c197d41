// Text files of example-based deformation: point constraints (or scan feature points), skinning
// weights, and the cache of a skinning decomposition.
//
// Both are plain text, one record per line. '#' starts a comment that runs to the end of the line;
// blank lines (and lines holding only a comment) are skipped; fields are separated by spaces or tabs;
// Windows line ends are accepted. Vertex indices are zero-based, in the order of the mesh files.
#pragma once

#include <posekit/mesh.hpp>
#include <posekit/skinning_decomposition.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace posekit {

/// Point constraints: the mesh vertex, its target position and an optional group label.
struct PointConstraints {
  std::vector<int> vertices;
  Eigen::MatrixX3d positions;       ///< one row per constraint
  std::vector<std::string> groups;  ///< "" for a constraint without a group
  std::vector<long> lines;          ///< the line each constraint came from
};

/// Reads "VERTEX X Y Z [GROUP]" lines. VERTEX lies in [0, vertex_count), X Y Z are finite numbers,
/// GROUP is any word: constraints that share a group name have known positions but an unknown
/// assignment of their vertices to those positions (see feature_correspondence.hpp). A vertex may
/// appear only once. Throws InputError naming the file and line for a malformed line, an index out of
/// range, a non-finite coordinate or a repeated vertex, and naming the file for an unreadable file or
/// one without any constraint.
PointConstraints read_point_constraints(const std::filesystem::path& file, int vertex_count);

/// Reads a vertex_count by m matrix of skinning weights: one line per vertex, in vertex order, each
/// with the same number m >= 1 of finite numbers, not all zero. Throws InputError naming the file and
/// line for a malformed row and naming the file when the row count differs from vertex_count.
Eigen::MatrixXd read_skinning_weights(const std::filesystem::path& file, int vertex_count);

/// Writes `decomposition` of `examples` to `file` whole or not at all (a temporary file, then a
/// rename), with the fingerprints of the connectivity and of the example poses that
/// read_skinning_decomposition() checks. Throws InputError naming the file when it cannot be written.
void write_skinning_decomposition(const std::filesystem::path& file, const SkinningDecomposition& decomposition,
                                  const PoseSet& examples);

/// Reads a decomposition written by write_skinning_decomposition() for these `examples`. Throws
/// InputError naming the file when it is unreadable or malformed (with the line), when it was made
/// for another mesh (vertex or face count, connectivity) or from other example poses.
SkinningDecomposition read_skinning_decomposition(const std::filesystem::path& file, const PoseSet& examples);

}  // namespace posekit
