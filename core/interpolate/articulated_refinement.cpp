#include "interpolate/articulated_refinement.hpp"

#include <posekit/edge_space.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace posekit::interpolation {
namespace {

constexpr double kRegularization = 1e-8;
constexpr int kLineSearchSteps = 8;

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace

ArticulatedRefinement::ArticulatedRefinement(const std::vector<const EdgeSpacePatch*>& joints,
                                             const std::vector<MeshComponent>& pieces, int vertex_count)
    : free_node_(static_cast<size_t>(vertex_count), -1),
      piece_of_(static_cast<size_t>(vertex_count), -1),
      piece_node_(pieces.size(), -1) {
  for (size_t p = 0; p < pieces.size(); ++p) {
    for (const int v : pieces[p].vertices) piece_of_[static_cast<size_t>(v)] = static_cast<int>(p);
    piece_vertices_.push_back(pieces[p].vertices);
  }
  // Nodes: one 3-block per free joint vertex, two (translation, rotation) per piece touching a joint.
  const auto node_of_vertex = [&](int v, std::vector<int>& nodes) {
    const int piece = piece_of_[static_cast<size_t>(v)];
    if (piece < 0) {
      if (free_node_[static_cast<size_t>(v)] < 0) free_node_[static_cast<size_t>(v)] = node_count_++;
      nodes.push_back(free_node_[static_cast<size_t>(v)]);
    } else {
      if (piece_node_[static_cast<size_t>(piece)] < 0) {
        piece_node_[static_cast<size_t>(piece)] = node_count_;
        node_count_ += 2;
      }
      nodes.push_back(piece_node_[static_cast<size_t>(piece)]);
      nodes.push_back(piece_node_[static_cast<size_t>(piece)] + 1);
    }
  };
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> nodes;
  const auto add_element = [&](Element element) {
    nodes.clear();
    const int corners[4] = {element.hinge.a, element.hinge.b, element.hinge.c, element.hinge.d};
    for (int i = 0; i < element.corners; ++i) node_of_vertex(corners[i], nodes);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    element.node_count = static_cast<int>(nodes.size());
    std::copy(nodes.begin(), nodes.end(), element.nodes);
    for (int i = 0; i < element.node_count; ++i) {
      for (int j = i + 1; j < element.node_count; ++j) pairs.emplace_back(element.nodes[i], element.nodes[j]);
    }
    elements_.push_back(element);
  };
  for (const EdgeSpacePatch* patch : joints) {
    const auto mesh_vertex = [&](int local) { return patch->vertices[static_cast<size_t>(local)]; };
    for (int e = 0; e < patch->edge_count(); ++e) {
      const int a = mesh_vertex(patch->edges(e, 0));
      const int b = mesh_vertex(patch->edges(e, 1));
      // An edge inside one piece keeps its length under a rigid motion.
      if (piece_of_[static_cast<size_t>(a)] >= 0 && piece_of_[static_cast<size_t>(a)] == piece_of_[static_cast<size_t>(b)]) continue;
      Element element;
      element.edge = patch->mesh_edges[static_cast<size_t>(e)];
      element.corners = 2;
      element.hinge.a = a;
      element.hinge.b = b;
      add_element(element);
    }
    for (int index = 0; index < patch->hinge_count(); ++index) {
      Hinge h = patch->hinges[static_cast<size_t>(index)];
      h.a = mesh_vertex(h.a);
      h.b = mesh_vertex(h.b);
      h.c = mesh_vertex(h.c);
      h.d = mesh_vertex(h.d);
      const int piece = piece_of_[static_cast<size_t>(h.a)];
      if (piece >= 0 && piece_of_[static_cast<size_t>(h.b)] == piece && piece_of_[static_cast<size_t>(h.c)] == piece &&
          piece_of_[static_cast<size_t>(h.d)] == piece) {
        continue;
      }
      Element element;
      element.edge = patch->mesh_hinges[static_cast<size_t>(index)];
      element.corners = 4;
      element.hinge = h;
      add_element(element);
    }
  }
  normal_matrix_ = BlockSparseMatrix3(node_count_, pairs);
  for (Element& element : elements_) {
    element.slot_offset = static_cast<int>(slots_.size());
    for (int i = 0; i < element.node_count; ++i) {
      for (int j = 0; j < element.node_count; ++j) slots_.push_back(normal_matrix_.slot(element.nodes[i], element.nodes[j]));
    }
  }
  if (node_count_ > 0) solver_.analyzePattern(normal_matrix_.matrix());
}

double ArticulatedRefinement::energy(const Eigen::Ref<const Eigen::MatrixX3d>& x, const Eigen::VectorXd& lengths,
                                     const Eigen::VectorXd& angles, double bending_weight) const {
  double sum = 0.0;
  for (const Element& element : elements_) {
    if (element.corners == 2) {
      const double target = lengths(element.edge);
      const double r = ((x.row(element.hinge.b) - x.row(element.hinge.a)).norm() - target) / target;
      sum += r * r;
    } else {
      const double r = wrap_angle(hinge_angle(element.hinge, x) - angles(element.edge));
      sum += bending_weight * r * r;
    }
  }
  return sum;
}

ArticulatedStats ArticulatedRefinement::refine(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths,
                                               const Eigen::VectorXd& angles, double bending_weight, int iterations,
                                               double tolerance) {
  ArticulatedStats stats;
  double current = energy(x, lengths, angles, bending_weight);
  stats.initial_energy = current;
  stats.final_energy = current;
  if (node_count_ == 0) return stats;
  const size_t piece_count = piece_vertices_.size();
  const int element_count = static_cast<int>(elements_.size());
  // Per element: the Jacobian row of its residual with respect to each of its nodes, and the residual.
  std::vector<Eigen::Matrix<double, 8, 3>> rows(static_cast<size_t>(element_count));
  std::vector<double> residuals(static_cast<size_t>(element_count));
  for (int iteration = 0; iteration < iterations && current > 0.0; ++iteration) {
    std::vector<Eigen::Vector3d> centres(piece_count, Eigen::Vector3d::Zero());
    for (size_t p = 0; p < piece_count; ++p) {
      if (piece_node_[p] < 0) continue;
      for (const int v : piece_vertices_[p]) centres[p] += x.row(v).transpose();
      centres[p] /= static_cast<double>(piece_vertices_[p].size());
    }
    tbb::parallel_for(0, element_count, [&](int index) {
      const Element& element = elements_[static_cast<size_t>(index)];
      Eigen::Matrix<double, 4, 3> corner_rows = Eigen::Matrix<double, 4, 3>::Zero();
      double r = 0.0;
      if (element.corners == 2) {
        const Eigen::Vector3d vector = x.row(element.hinge.b) - x.row(element.hinge.a);
        const double length = vector.norm();
        const double target = lengths(element.edge);
        r = (length - target) / target;
        if (length > 0.0) {
          corner_rows.row(1) = vector.transpose() / (length * target);
          corner_rows.row(0) = -corner_rows.row(1);
        }
      } else {
        const double scale = std::sqrt(bending_weight);
        r = scale * wrap_angle(hinge_angle(element.hinge, x) - angles(element.edge));
        corner_rows = scale * hinge_angle_gradient(element.hinge, x);
      }
      residuals[static_cast<size_t>(index)] = r;
      Eigen::Matrix<double, 8, 3>& out = rows[static_cast<size_t>(index)];
      out.setZero();
      const int corners[4] = {element.hinge.a, element.hinge.b, element.hinge.c, element.hinge.d};
      for (int i = 0; i < element.corners; ++i) {
        const int v = corners[i];
        const int piece = piece_of_[static_cast<size_t>(v)];
        const auto position = [&](int node) {
          return static_cast<int>(std::find(element.nodes, element.nodes + element.node_count, node) - element.nodes);
        };
        if (piece < 0) {
          out.row(position(free_node_[static_cast<size_t>(v)])) += corner_rows.row(i);
        } else {
          // x_v moves with its piece: dx = dt + dw x (x_v - c) = dt - [x_v - c]_x dw.
          const int node = piece_node_[static_cast<size_t>(piece)];
          const Eigen::Vector3d arm = x.row(v).transpose() - centres[static_cast<size_t>(piece)];
          out.row(position(node)) += corner_rows.row(i);
          out.row(position(node + 1)) += -corner_rows.row(i) * cross_matrix(arm);
        }
      }
    });
    normal_matrix_.set_zero();
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(3 * node_count_);
    for (int index = 0; index < element_count; ++index) {
      const Element& element = elements_[static_cast<size_t>(index)];
      const Eigen::Matrix<double, 8, 3>& j = rows[static_cast<size_t>(index)];
      const double r = residuals[static_cast<size_t>(index)];
      const BlockSparseMatrix3::Slot* slots = &slots_[static_cast<size_t>(element.slot_offset)];
      for (int a = 0; a < element.node_count; ++a) {
        gradient.segment<3>(3 * element.nodes[a]) += r * j.row(a).transpose();
        for (int b = 0; b < element.node_count; ++b) {
          normal_matrix_.add(slots[a * element.node_count + b], j.row(a).transpose() * j.row(b));
        }
      }
    }
    const double damping = kRegularization * std::max(normal_matrix_.mean_diagonal(), 1e-300);
    for (int n = 0; n < node_count_; ++n) normal_matrix_.add_diagonal(n, damping);
    solver_.factorize(normal_matrix_.matrix());
    if (solver_.info() != Eigen::Success) break;
    const Eigen::VectorXd step = -solver_.solve(gradient);
    if (!step.allFinite()) break;
    const auto moved = [&](double scale) {
      Eigen::MatrixX3d y = x;
      for (size_t v = 0; v < free_node_.size(); ++v) {
        if (free_node_[v] >= 0) y.row(static_cast<Eigen::Index>(v)) += scale * step.segment<3>(3 * free_node_[v]).transpose();
      }
      for (size_t p = 0; p < piece_count; ++p) {
        if (piece_node_[p] < 0) continue;
        const Eigen::Vector3d shift = scale * step.segment<3>(3 * piece_node_[p]);
        const Eigen::Vector3d turn = scale * step.segment<3>(3 * piece_node_[p] + 3);
        const double angle = turn.norm();
        const Eigen::Matrix3d rotation =
            angle > 0.0 ? Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
        for (const int v : piece_vertices_[p]) {
          y.row(v) = (centres[p] + shift + rotation * (x.row(v).transpose() - centres[p])).transpose();
        }
      }
      return y;
    };
    double scale = 1.0;
    bool accepted = false;
    Eigen::MatrixX3d trial;
    double trial_energy = current;
    for (int attempt = 0; attempt < kLineSearchSteps; ++attempt, scale *= 0.5) {
      trial = moved(scale);
      trial_energy = energy(trial, lengths, angles, bending_weight);
      if (trial_energy < current) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    x = std::move(trial);
    ++stats.iterations;
    const double decrease = current - trial_energy;
    current = trial_energy;
    if (decrease < tolerance * (current + decrease)) break;
  }
  stats.final_energy = current;
  return stats;
}

}  // namespace posekit::interpolation
