// Regions of a mesh's vertices: rings around a flagged set, its connected parts, and parts joined
// where they intersect. Repairs grow such regions around intersecting faces.
#pragma once

#include <posekit/self_intersection_tracker.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// Edge distance of every vertex from the flagged ones (0 for those), -1 beyond `limit` edges.
std::vector<int> ring_distances(const std::vector<char>& flagged, const AdjacencyLists& neighbours, int limit);

/// One flag per vertex (`vertex_count` of them), set on the corners of the faces in `face_list`.
std::vector<char> face_vertices(const std::vector<int>& face_list, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                size_t vertex_count);

/// The flagged vertices and every vertex within `rings` edges of one.
std::vector<char> within_rings(const std::vector<char>& flagged, const AdjacencyLists& neighbours, int rings);

/// One flag per face of `faces`: set where all three corners are flagged.
std::vector<char> faces_within(const std::vector<char>& flagged, const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Whether a face of `face_list` has a flagged corner.
bool touches(const std::vector<char>& flagged, const std::vector<int>& face_list,
             const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// The connected sets of flagged vertices (through edges between flagged vertices), largest first.
std::vector<std::vector<int>> connected_sets(const std::vector<char>& flagged, const AdjacencyLists& neighbours);

/// The flagged region and every part of the mesh it cuts off: in each connected piece of the mesh,
/// the unflagged vertices fall into connected sets, and all but the largest (of equal ones, that with
/// the lowest vertex) join the region: a tail's tip beyond a band around the tail. One flag per vertex.
std::vector<char> with_cut_off_parts(std::vector<char> region, const AdjacencyLists& neighbours);

/// `sets` (disjoint vertex sets) joined wherever a face with a corner in one intersects a face with a
/// corner in another (`pairs` of faces of `faces`): both sides of an intersection are one problem.
/// Largest first.
std::vector<std::vector<int>> join_intersecting(const std::vector<std::vector<int>>& sets, const FacePairs& pairs,
                                                const Eigen::Ref<const Eigen::MatrixX3i>& faces);

}  // namespace posekit
