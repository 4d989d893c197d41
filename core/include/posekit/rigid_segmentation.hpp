// Segmentation of a pose set into parts that move rigidly across all its poses, and part labels
// given by the user. Parts are face sets; every part returned here is connected through edges.
#pragma once

#include <posekit/mesh.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <filesystem>

namespace posekit {

/// Parameters of segment_rigid_parts().
struct SegmentationOptions {
  /// A part grows from its most rigid face over neighbouring faces whose rotation (from pose 0 to
  /// each other pose) differs from that face's by at most this angle in every pose (degrees, in (0, 180)).
  double rigidity_angle_degrees = 30.0;
  /// Parts with fewer faces than this fraction of all faces (and at least 10 faces) are merged into the
  /// neighbouring part they share most edges with (in [0, 1)); noise does not make its own parts.
  double min_part_fraction = 0.002;
};

/// #F part ids (0 .. P-1), each part connected through edges, found from how the faces of the #F by 3
/// face list rotate across all poses of `poses` (at least two): the rotation of each face from pose 0
/// to pose k is the rotation of its deformation gradient's polar decomposition, and parts grow by
/// region growing from the most rigid faces. Deterministic. Throws ArgumentError for fewer than two
/// poses or options out of range.
Eigen::VectorXi segment_rigid_parts(const PoseSet& poses, const SegmentationOptions& options = {});

/// Relabels the #F `face_labels` (any integers) so that every part is connected through the edges of
/// `edges` (edge_map of the faces, with `incident_faces` = edge_faces(edges)): a label whose faces
/// fall apart gives one part per piece. Returns ids 0 .. P-1 in the order of each part's first face.
Eigen::VectorXi connected_parts(const Eigen::VectorXi& face_labels, const EdgeMap& edges,
                                const AdjacencyLists& incident_faces);

/// Per-face labels from #V per-vertex labels of the #F by 3 `faces`: each face takes the label most
/// of its corners have (the smallest of three different ones).
Eigen::VectorXi face_labels_from_vertex_labels(const Eigen::VectorXi& vertex_labels,
                                               const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Reads a part label file: non-negative integer part ids separated by white space ('#' starts a
/// comment), one per vertex (#V ids) or one per face (#F ids; read as per-face when #V = #F), and
/// returns #F per-face labels. Throws InputError naming `file` when it cannot be read, holds
/// something else than such ids, or holds neither #V nor #F of them.
Eigen::VectorXi read_part_labels(const std::filesystem::path& file, int vertex_count,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Writes one part id per face, one per line, whole or not at all (InputError naming `file` on failure).
void write_part_labels(const std::filesystem::path& file, const Eigen::VectorXi& face_labels);

}  // namespace posekit
