// Per-pose geometric quantities: bounding box, face normals and areas, edge stretch, dihedral
// angles, and the unit-sphere normalization that puts several poses into one common frame.
#pragma once

#include <posekit/mesh.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// Length of the diagonal of the axis-aligned bounding box of the #V by 3 `vertices`.
/// Throws ArgumentError when there is no vertex or a coordinate is not finite.
double bounding_box_diagonal(const Eigen::Ref<const Eigen::MatrixX3d>& vertices);

/// #F by 3 unit normals of the faces (right-hand rule over the corner order) of the #V by 3 `vertices`
/// and #F by 3 `faces`. A degenerate face (zero area) gets a zero row. Throws ArgumentError on a bad index.
Eigen::MatrixX3d face_normals(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// #F areas of the faces of the #V by 3 `vertices` and #F by 3 `faces`. Throws ArgumentError on a bad index.
Eigen::VectorXd face_areas(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                           const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// #V by 3 unit vertex normals: the area-weighted sum of the normals of the faces around each vertex.
/// A vertex without a face of non-zero area gets a zero row. Throws ArgumentError on a bad index.
Eigen::MatrixX3d vertex_normals(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// #E lengths of the #E by 2 `edges` (rows of edge_map) of the #V by 3 `vertices`.
Eigen::VectorXd edge_lengths(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                             const Eigen::Ref<const Eigen::MatrixX2i>& edges);

/// Per face of `faces`, the largest ratio of an edge's length in `pose` to the longer of its lengths in
/// `first` and `second` (#V by 3 each) and `shortest` (>= 0): how much a face grew beyond both of two
/// poses, as a corrected pose against its reference and target (2: an edge twice as long as in
/// either). The floor keeps a sliver that opens to an ordinary face from counting as a spike. An edge
/// of no length anywhere counts 1, infinity once it has one. Throws ArgumentError on bad arguments.
Eigen::VectorXd edge_stretch(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                             const Eigen::Ref<const Eigen::MatrixX3d>& first,
                             const Eigen::Ref<const Eigen::MatrixX3d>& second,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces, double shortest = 0.0);

/// Signed dihedral angle in radians, in [-pi, pi], of every edge of `edges` (edge_map(faces)), with
/// `incident_faces` = edge_faces(edges): the angle between the normals of the edge's two faces, 0 where
/// the surface is flat, positive where it is convex (folds away from its normals, as at the edges of a
/// tetrahedron: about +1.911 there), negative where concave. When the two faces run through the edge in
/// the same direction (inconsistent orientation) the second face is flipped to agree with the first.
/// An edge with one face (boundary) or more than two (non-manifold) gets NaN; a degenerate face gives 0.
/// `vertices` is #V by 3, `faces` #F by 3; returns #E values. Throws ArgumentError on mismatched sizes.
Eigen::VectorXd dihedral_angles(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const EdgeMap& edges, const AdjacencyLists& incident_faces);

/// The same for a single pose: computes edge_map(faces) itself; values follow its edge order.
Eigen::VectorXd dihedral_angles(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// A similarity that maps poses into the unit sphere: x -> (x - center) * scale.
struct UnitSphereNormalization {
  Eigen::RowVector3d center = Eigen::RowVector3d::Zero();
  double scale = 1.0;

  /// #V by 3 normalized copy of the #V by 3 `vertices`.
  Eigen::MatrixX3d apply(const Eigen::Ref<const Eigen::MatrixX3d>& vertices) const;
  /// Inverse of apply(): #V by 3 positions back in the original frame.
  Eigen::MatrixX3d undo(const Eigen::Ref<const Eigen::MatrixX3d>& normalized) const;
  /// A length measured in the original frame, expressed in the normalized one.
  double apply_to_length(double length) const { return length * scale; }
};

/// The normalization of the #V by 3 `vertices`: center = center of their axis-aligned bounding box,
/// scale = 1 / (largest distance of a vertex from that center), so every vertex lands in the closed
/// unit ball and the farthest one on the unit sphere. Throws ArgumentError when there is no vertex, a
/// coordinate is not finite, or all vertices coincide.
UnitSphereNormalization unit_sphere_normalization(const Eigen::Ref<const Eigen::MatrixX3d>& vertices);

/// One normalization for several poses (each #V_i by 3): the bounding box and the farthest vertex are
/// taken over all of them, so each pose lands in the unit ball and they keep their relative placement
/// (what pose correction needs for its reference and target). Same errors as above, also for no pose.
UnitSphereNormalization shared_unit_sphere_normalization(
    const std::vector<Eigen::Ref<const Eigen::MatrixX3d>>& poses);

/// shared_unit_sphere_normalization over every pose of `poses`.
UnitSphereNormalization shared_unit_sphere_normalization(const PoseSet& poses);

/// Farthest-point sampling: `seeds`, then vertices each farthest from all chosen so far, up to
/// `count` in all; with no seed the first is the vertex farthest from the centroid. Indices into
/// `vertices` (#V by 3); fewer than `count` only when the mesh has fewer vertices.
std::vector<int> farthest_point_samples(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, int count,
                                        std::vector<int> seeds = {});

}  // namespace posekit
