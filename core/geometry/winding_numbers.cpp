#include <posekit/winding_numbers.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace posekit {
namespace {

// Van Oosterom and Strackee's formula for the solid angle of a triangle seen from `point`.
double solid_angle(const Eigen::Vector3d& point, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = a - point;
  const Eigen::Vector3d v = b - point;
  const Eigen::Vector3d w = c - point;
  const double lu = u.norm();
  const double lv = v.norm();
  const double lw = w.norm();
  // A corner of the triangle itself: the triangle is seen edge on.
  if (lu == 0.0 || lv == 0.0 || lw == 0.0) return 0.0;
  const double numerator = u.dot(v.cross(w));
  const double denominator = lu * lv * lw + u.dot(v) * lw + v.dot(w) * lu + w.dot(u) * lv;
  return 2.0 * std::atan2(numerator, denominator);
}

// Faces per leaf of the tree: below this, exact solid angles are cheaper than descending.
constexpr int kLeafFaces = 8;
// A cluster whose centre is farther than this many of its radii from the point is replaced by its
// dipole (Barill et al., fast winding numbers): the error falls with the square of the ratio, and
// at four it stays within 0.02 of the exact sum, far below the half that separates inside
// from outside.
constexpr double kFarRatio = 4.0;
// Subtrees over at least this many faces build their two halves in parallel.
constexpr int kParallelBuildFaces = 4096;

// A bounding-volume hierarchy of the faces whose nodes know the dipole of their faces: the sum of
// the area vectors (twice the area times the unit normal, halved) and their area-weighted centre.
class DipoleTree {
 public:
  DipoleTree(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
             const Eigen::Ref<const Eigen::MatrixX3i>& faces) : vertices_(vertices), faces_(faces) {
    const auto count = static_cast<int>(faces.rows());
    order_.resize(static_cast<size_t>(count));
    std::iota(order_.begin(), order_.end(), 0);
    centroids_.resize(static_cast<size_t>(count));
    area_vectors_.resize(static_cast<size_t>(count));
    areas_.resize(static_cast<size_t>(count));
    tbb::parallel_for(0, count, [&](int f) {
      const Eigen::Vector3d a = vertices.row(faces(f, 0)).transpose();
      const Eigen::Vector3d b = vertices.row(faces(f, 1)).transpose();
      const Eigen::Vector3d c = vertices.row(faces(f, 2)).transpose();
      const auto face = static_cast<size_t>(f);
      centroids_[face] = (a + b + c) / 3.0;
      area_vectors_[face] = 0.5 * (b - a).cross(c - a);
      areas_[face] = area_vectors_[face].norm();
    });
    if (count > 0) {
      nodes_.resize(static_cast<size_t>(node_count(count)));
      build(0, 0, count, 1);
    }
  }

  double winding_number(const Eigen::Vector3d& point) const {
    if (nodes_.empty()) return 0.0;
    double sum = 0.0;
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const Node& node = nodes_[static_cast<size_t>(stack.back())];
      stack.pop_back();
      const Eigen::Vector3d offset = node.center - point;
      const double distance = offset.norm();
      if (distance > kFarRatio * node.radius) {
        // Dipole: the solid angle of a small oriented area A seen from distance r is A . r / |r|^3.
        sum += node.area_vector.dot(offset) / (distance * distance * distance);
        continue;
      }
      if (node.first_child < 0) {
        for (int i = node.begin; i < node.end; ++i) {
          const int f = order_[static_cast<size_t>(i)];
          sum += solid_angle(point, vertices_.row(faces_(f, 0)).transpose(), vertices_.row(faces_(f, 1)).transpose(),
                             vertices_.row(faces_(f, 2)).transpose());
        }
        continue;
      }
      stack.push_back(node.first_child);
      stack.push_back(node.first_child + 1);
    }
    return sum / (4.0 * M_PI);
  }

 private:
  struct Node {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();       // area-weighted centre of its faces
    Eigen::Vector3d area_vector = Eigen::Vector3d::Zero();  // sum of their area vectors
    double radius = 0.0;                                     // farthest corner from the centre
    int begin = 0, end = 0;                                  // its faces: order_[begin, end)
    int first_child = -1;                                    // the two children, adjacent; -1: a leaf
  };

  // Nodes of the subtree over `faces` faces: the split halves them until a leaf holds kLeafFaces.
  static int node_count(int faces) {
    return faces > kLeafFaces ? 1 + node_count(faces / 2) + node_count(faces - faces / 2) : 1;
  }

  // Fills node `slot` over order_[begin, end) and builds its subtree, whose further nodes take the
  // slots from `next` on: a node's two children side by side, then the first child's subtree, then
  // the second's. The slots are known before the halves are built, so the halves are built side by
  // side and the tree is the same as built in one thread.
  void build(int slot, int begin, int end, int next) {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double area = 0.0;
    Node node;
    node.begin = begin;
    node.end = end;
    for (int i = begin; i < end; ++i) {
      const auto f = static_cast<size_t>(order_[static_cast<size_t>(i)]);
      const double a = areas_[f];
      weighted += a * centroids_[f];
      area += a;
      node.area_vector += area_vectors_[f];
      low = low.cwiseMin(centroids_[f]);
      high = high.cwiseMax(centroids_[f]);
    }
    node.center = area > 0.0 ? Eigen::Vector3d(weighted / area) : Eigen::Vector3d(0.5 * (low + high));
    for (int i = begin; i < end; ++i) {
      const int f = order_[static_cast<size_t>(i)];
      for (int c = 0; c < 3; ++c) {
        node.radius = std::max(node.radius, (vertices_.row(faces_(f, c)).transpose() - node.center).norm());
      }
    }
    if (end - begin > kLeafFaces) {
      // Median split of the centroids along the longest side.
      int axis = 0;
      (high - low).maxCoeff(&axis);
      const int middle = begin + (end - begin) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int a, int b) {
        return centroids_[static_cast<size_t>(a)](axis) < centroids_[static_cast<size_t>(b)](axis);
      });
      node.first_child = next;
      const int first_subtree = next + 2;
      const int second_subtree = first_subtree + node_count(middle - begin) - 1;
      const auto first = [&] { build(node.first_child, begin, middle, first_subtree); };
      const auto second = [&] { build(node.first_child + 1, middle, end, second_subtree); };
      if (end - begin >= kParallelBuildFaces) {
        tbb::parallel_invoke(first, second);
      } else {
        first();
        second();
      }
    }
    nodes_[static_cast<size_t>(slot)] = node;
  }

  const Eigen::Ref<const Eigen::MatrixX3d> vertices_;
  const Eigen::Ref<const Eigen::MatrixX3i> faces_;
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centroids_;
  std::vector<Eigen::Vector3d> area_vectors_;
  std::vector<double> areas_;  // the norms of area_vectors_, read at every level of the build
  std::vector<Node> nodes_;
};

Eigen::VectorXd winding_numbers_in(const DipoleTree& tree, const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  Eigen::VectorXd winding(points.rows());
  tbb::parallel_for(Eigen::Index{0}, points.rows(),
                    [&](Eigen::Index p) { winding(p) = tree.winding_number(points.row(p).transpose()); });
  return winding;
}

}  // namespace

// The tree over the surface's own copy, which it keeps as long as the tree lives.
class WindingNumberTree::Tree {
 public:
  Tree(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces)
      : vertices_(vertices), faces_(faces), dipoles_(vertices_, faces_) {}
  // The dipole tree views this object's matrices: a copy would view the original's.
  Tree(const Tree&) = delete;
  Tree& operator=(const Tree&) = delete;
  Tree(Tree&&) = delete;
  Tree& operator=(Tree&&) = delete;
  ~Tree() = default;
  const DipoleTree& dipoles() const { return dipoles_; }

 private:
  Eigen::MatrixX3d vertices_;
  Eigen::MatrixX3i faces_;
  DipoleTree dipoles_;
};

WindingNumberTree::WindingNumberTree(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                     const Eigen::Ref<const Eigen::MatrixX3i>& faces)
    : tree_(std::make_unique<Tree>(vertices, faces)) {}
WindingNumberTree::~WindingNumberTree() = default;
WindingNumberTree::WindingNumberTree(WindingNumberTree&&) noexcept = default;
WindingNumberTree& WindingNumberTree::operator=(WindingNumberTree&&) noexcept = default;

Eigen::VectorXd WindingNumberTree::at(const Eigen::Ref<const Eigen::MatrixX3d>& points) const {
  return winding_numbers_in(tree_->dipoles(), points);
}

Eigen::VectorXd winding_numbers(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  return winding_numbers_in(DipoleTree(vertices, faces), points);
}

}  // namespace posekit
