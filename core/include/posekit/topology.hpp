// Connectivity of a triangle mesh: unique edges, face-edge and edge-face maps, vertex one-rings.
// Everything here depends on the face list only, so one result serves every pose of a PoseSet.
// Non-manifold meshes are fine: an edge may border any number of faces.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// A contiguous, read-only run of indices inside AdjacencyLists.
class IndexRange {
 public:
  IndexRange(const int* first, const int* last) : first_(first), last_(last) {}
  const int* begin() const { return first_; }
  const int* end() const { return last_; }
  int size() const { return static_cast<int>(last_ - first_); }
  bool empty() const { return first_ == last_; }
  int operator[](int position) const { return first_[position]; }

 private:
  const int* first_;
  const int* last_;
};

/// One list of indices per item, stored back to back (compressed sparse rows): the list of item i
/// is indices()[offsets()[i] .. offsets()[i + 1]). Each list is sorted ascending.
class AdjacencyLists {
 public:
  AdjacencyLists() : offsets_(1, 0) {}
  /// `offsets` has item_count() + 1 non-decreasing entries starting at 0 and ending at indices.size();
  /// throws ArgumentError otherwise.
  AdjacencyLists(std::vector<int> offsets, std::vector<int> indices);

  /// Number of items (lists).
  int item_count() const { return static_cast<int>(offsets_.size()) - 1; }
  /// Length of the list of `item` (0 <= item < item_count(), unchecked).
  int count(int item) const { return offsets_[static_cast<size_t>(item) + 1] - offsets_[static_cast<size_t>(item)]; }
  /// The list of `item` (0 <= item < item_count(), unchecked).
  IndexRange operator[](int item) const {
    const int* base = indices_.data();
    return {base + offsets_[static_cast<size_t>(item)], base + offsets_[static_cast<size_t>(item) + 1]};
  }
  const std::vector<int>& offsets() const { return offsets_; }
  const std::vector<int>& indices() const { return indices_; }

 private:
  std::vector<int> offsets_;
  std::vector<int> indices_;
};

/// The unique undirected edges of a face list and, per face, which edges bound it.
struct EdgeMap {
  /// #E by 2 vertex indices, each row sorted (first < second), rows in lexicographic order.
  /// A face that repeats a vertex contributes an edge whose two entries are equal.
  Eigen::MatrixX2i edges;
  /// #F by 3 edge indices: column k of face f is the edge between its corners k and (k + 1) % 3.
  Eigen::MatrixX3i face_edges;
};

/// Unique edges of the #F by 3 face list `faces` and the face-to-edge map, in O(#F log #F).
/// Throws ArgumentError when a vertex index is negative.
EdgeMap edge_map(const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Faces incident to each edge of `edges` (edge_map(faces) of the same #F by 3 `faces`), ascending.
/// An interior manifold edge has 2 faces, a boundary edge 1, a non-manifold edge 3 or more; a face
/// that uses the same edge twice (a repeated vertex) is listed once.
AdjacencyLists edge_faces(const EdgeMap& edges);

/// One-ring of each vertex: the distinct vertices sharing an edge with it, ascending, never itself.
/// `faces` is #F by 3 with indices below `vertex_count`; throws ArgumentError otherwise.
AdjacencyLists vertex_neighbours(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count);

/// Faces incident to each vertex, ascending and distinct (#V lists for `vertex_count` vertices).
/// `faces` is #F by 3 with indices below `vertex_count`; throws ArgumentError otherwise.
AdjacencyLists vertex_faces(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count);

/// Throws ArgumentError unless every entry of the #F by 3 `faces` lies in [0, vertex_count).
/// The message names the first offending face and corner.
void check_face_indices(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count);

}  // namespace posekit
