#include <posekit/error.hpp>
#include <posekit/face_deformation.hpp>
#include <posekit/poisson_interpolation.hpp>
#include <posekit/rigid_motion.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_for.h>

#include <cmath>

namespace posekit {
namespace {

// Translation (per connected component) is not fixed by gradients; a weak pull towards linear
// interpolation of the vertices fixes it without visibly bending the shape.
constexpr double kAnchorWeight = 1e-8;

struct FaceFrame {
  Eigen::Matrix3d gradient_operator;  // columns: gradients of the three hat functions
  double area = 0.0;
};

}  // namespace

struct PoissonInterpolator::State {
  Eigen::MatrixX3i faces;
  Eigen::MatrixX3d source;
  Eigen::MatrixX3d target;
  std::vector<FaceFrame> frames;
  std::vector<Eigen::Vector3d> rotation_logs;  // per face, branch chosen consistently across neighbours
  std::vector<Eigen::Matrix3d> stretches;      // per face, symmetric
  Eigen::VectorXd anchor_weights;              // per vertex
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
};

PoissonInterpolator::PoissonInterpolator(const Eigen::Ref<const Eigen::MatrixX3d>& source,
                                         const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& faces)
    : state_(std::make_unique<State>()) {
  if (source.rows() != target.rows()) {
    throw ArgumentError("PoissonInterpolator: source has " + std::to_string(source.rows()) +
                        " vertices but target has " + std::to_string(target.rows()));
  }
  const int vertex_count = static_cast<int>(source.rows());
  check_face_indices(faces, vertex_count);
  State& s = *state_;
  s.faces = faces;
  s.source = source;
  s.target = target;
  const int face_count = static_cast<int>(faces.rows());
  s.frames.resize(static_cast<size_t>(face_count));
  s.stretches.resize(static_cast<size_t>(face_count));
  std::vector<Eigen::AngleAxisd> rotations(static_cast<size_t>(face_count));

  tbb::parallel_for(0, face_count, [&](int f) {
    const Eigen::Vector3d a = source.row(faces(f, 0));
    const Eigen::Vector3d b = source.row(faces(f, 1));
    const Eigen::Vector3d c = source.row(faces(f, 2));
    FaceFrame& frame = s.frames[static_cast<size_t>(f)];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double twice_area = cross.norm();
    frame.area = 0.5 * twice_area;
    Eigen::Matrix3d deformation = Eigen::Matrix3d::Identity();
    if (twice_area > 0.0) {
      // Hat-function gradients: n x (opposite edge) / (2 A).
      const Eigen::Vector3d normal = cross / twice_area;
      frame.gradient_operator.col(0) = normal.cross(c - b) / twice_area;
      frame.gradient_operator.col(1) = normal.cross(a - c) / twice_area;
      frame.gradient_operator.col(2) = normal.cross(b - a) / twice_area;
      const Eigen::Matrix3d source_basis = face_basis(a, b, c);
      const Eigen::Matrix3d target_basis =
          face_basis(target.row(faces(f, 0)), target.row(faces(f, 1)), target.row(faces(f, 2)));
      deformation = target_basis * source_basis.inverse();
    } else {
      frame.gradient_operator.setZero();  // a degenerate face constrains nothing
    }
    const PolarDecomposition polar = polar_decomposition(deformation);
    s.stretches[static_cast<size_t>(f)] = polar.stretch;
    rotations[static_cast<size_t>(f)] = Eigen::AngleAxisd(polar.rotation);
  });
  s.rotation_logs = consistent_rotation_logs(rotations, faces);

  // Stiffness sum_f A_f G_f^T G_f (the cotangent Laplacian) plus the weak anchor.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(face_count) * 9 + static_cast<size_t>(vertex_count));
  s.anchor_weights = Eigen::VectorXd::Zero(vertex_count);
  double diagonal_scale = 0.0;
  for (int f = 0; f < face_count; ++f) {
    const FaceFrame& frame = s.frames[static_cast<size_t>(f)];
    const Eigen::Matrix3d local = frame.area * frame.gradient_operator.transpose() * frame.gradient_operator;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) entries.emplace_back(faces(f, i), faces(f, j), local(i, j));
      diagonal_scale += local(i, i);
      s.anchor_weights(faces(f, i)) += frame.area / 3.0;
    }
  }
  const double mean_diagonal = vertex_count > 0 ? diagonal_scale / vertex_count : 1.0;
  const double mean_mass = vertex_count > 0 ? s.anchor_weights.sum() / vertex_count : 1.0;
  for (int v = 0; v < vertex_count; ++v) {
    // Vertices of degenerate faces only (or of none) still get a positive anchor.
    const double mass = s.anchor_weights(v) > 0.0 ? s.anchor_weights(v) : mean_mass;
    s.anchor_weights(v) = kAnchorWeight * (mean_diagonal > 0.0 ? mean_diagonal : 1.0) * mass /
                          (mean_mass > 0.0 ? mean_mass : 1.0);
    entries.emplace_back(v, v, s.anchor_weights(v));
  }
  Eigen::SparseMatrix<double> stiffness(vertex_count, vertex_count);
  stiffness.setFromTriplets(entries.begin(), entries.end());
  s.solver.compute(stiffness);
  if (s.solver.info() != Eigen::Success) {
    throw Error("PoissonInterpolator: the sparse factorization failed");
  }
}

PoissonInterpolator::~PoissonInterpolator() = default;
PoissonInterpolator::PoissonInterpolator(PoissonInterpolator&&) noexcept = default;
PoissonInterpolator& PoissonInterpolator::operator=(PoissonInterpolator&&) noexcept = default;

Eigen::MatrixX3d PoissonInterpolator::at(double t) const {
  const State& s = *state_;
  const int vertex_count = static_cast<int>(s.source.rows());
  const int face_count = static_cast<int>(s.faces.rows());
  const Eigen::MatrixX3d linear = (1.0 - t) * s.source + t * s.target;
  Eigen::MatrixX3d rhs = s.anchor_weights.asDiagonal() * linear;

  // Desired per-face gradients of the coordinates: the interpolated deformation applied to the
  // source's own (tangent-plane) gradient.
  std::vector<Eigen::Matrix3d> contributions(static_cast<size_t>(face_count));
  tbb::parallel_for(0, face_count, [&](int f) {
    const FaceFrame& frame = s.frames[static_cast<size_t>(f)];
    const Eigen::Vector3d log = s.rotation_logs[static_cast<size_t>(f)];
    const double angle = log.norm();
    const Eigen::Matrix3d rotation =
        angle > 0.0 ? Eigen::AngleAxisd(t * angle, log / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d stretch =
        (1.0 - t) * Eigen::Matrix3d::Identity() + t * s.stretches[static_cast<size_t>(f)];
    const Eigen::Matrix3d deformation = rotation * stretch;
    Eigen::Matrix3d source_corners;
    for (int corner = 0; corner < 3; ++corner) source_corners.row(corner) = s.source.row(s.faces(f, corner));
    // Source gradient of the coordinates (3 x 3, column c = gradient of coordinate c).
    const Eigen::Matrix3d source_gradient = frame.gradient_operator * source_corners;
    const Eigen::Matrix3d desired = source_gradient * deformation.transpose();
    contributions[static_cast<size_t>(f)] = frame.area * frame.gradient_operator.transpose() * desired;
  });
  for (int f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      rhs.row(s.faces(f, corner)) += contributions[static_cast<size_t>(f)].row(corner);
    }
  }
  Eigen::MatrixX3d result(vertex_count, 3);
  for (int c = 0; c < 3; ++c) result.col(c) = s.solver.solve(rhs.col(c));
  return result;
}

std::vector<Eigen::MatrixX3d> PoissonInterpolator::key_frames(int count) const {
  if (count < 2) throw ArgumentError("key frame count must be at least 2, got " + std::to_string(count));
  std::vector<Eigen::MatrixX3d> frames;
  frames.reserve(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) frames.push_back(at(static_cast<double>(i) / (count - 1)));
  return frames;
}

}  // namespace posekit
