// Stitching aligned components into one mesh by least squares on edge vectors (the edge blending of
// Winkler et al.): vertices of rigid pieces keep their aligned positions; every other vertex (inside
// joints) is placed so that the edges of every component holding it match that component's edge
// vectors, scaled to the interpolated length where components overlap. The normal matrix depends only
// on the layout, so it is factorized once.
#pragma once

#include "interpolate/joint_layout.hpp"

#include <posekit/topology.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include <vector>

namespace posekit::interpolation {

class EdgeStitching {
 public:
  /// `components` (faces and ascending vertices) of a mesh with `vertex_count` vertices and
  /// `edges` = edge_map of its faces; vertices flagged in `held` (#V flags) keep the position their
  /// components give them.
  EdgeStitching(const EdgeMap& edges, const std::vector<MeshComponent>& components, const std::vector<char>& held,
                int vertex_count);

  /// #V by 3 positions from the placed component shapes (rows in component vertex order) and the #E
  /// interpolated edge lengths. Vertices of no component are left at zero.
  Eigen::MatrixX3d stitch(const std::vector<Eigen::MatrixX3d>& placed, const Eigen::VectorXd& target_lengths) const;

 private:
  struct ComponentEdge {
    int edge;  // mesh edge
    int from;  // rows of the component's shape: the mesh edge's first and second vertex
    int to;
  };
  std::vector<std::vector<ComponentEdge>> component_edges_;
  std::vector<std::vector<int>> component_vertices_;
  std::vector<char> holding_;  // per component: all its vertices are held (a rigid piece)
  std::vector<int> holders_;   // per mesh edge: components holding it
  std::vector<int> unknown_;   // per vertex: its row among the unknowns, or -1 when held
  Eigen::MatrixX2i edges_;
  int vertex_count_ = 0;
  int unknown_count_ = 0;
  double anchor_ = 0.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace posekit::interpolation
