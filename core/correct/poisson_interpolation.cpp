#include <posekit/error.hpp>
#include <posekit/poisson_interpolation.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_for.h>

#include <cmath>
#include <queue>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Translation (per connected component) is not fixed by gradients; a weak pull towards linear
// interpolation of the vertices fixes it without visibly bending the shape.
constexpr double kAnchorWeight = 1e-8;

struct FaceFrame {
  Eigen::Matrix3d gradient_operator;  // columns: gradients of the three hat functions
  double area = 0.0;
};

// A face's edge vectors plus its normal scaled to the square root of twice the area, so that the
// deformation gradient treats the normal direction like the in-plane ones.
Eigen::Matrix3d face_basis(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a;
  const Eigen::Vector3d e2 = c - a;
  const Eigen::Vector3d cross = e1.cross(e2);
  const double norm = cross.norm();
  Eigen::Matrix3d basis;
  basis.col(0) = e1;
  basis.col(1) = e2;
  basis.col(2) = norm > 0.0 ? Eigen::Vector3d(cross / std::sqrt(norm)) : Eigen::Vector3d::Zero();
  return basis;
}

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

namespace {

// Below this angle the principal logarithm is unambiguous and varies continuously between faces.
constexpr double kUnambiguousAngle = 0.9 * kPi;

// A rotation by nearly pi has two logarithms far apart (theta * axis and (theta - 2 pi) * axis);
// picking them face by face would send neighbours around opposite ways. Faces rotated by less than
// kUnambiguousAngle keep their principal logarithm; the others are reached breadth-first from them
// and take the branch closest to the mean of their already-assigned neighbours.
std::vector<Eigen::Vector3d> consistent_rotation_logs(const std::vector<Eigen::AngleAxisd>& rotations,
                                                      const Eigen::MatrixX3i& faces) {
  const int face_count = static_cast<int>(faces.rows());
  const EdgeMap edges = edge_map(faces);
  const AdjacencyLists faces_of_edge = edge_faces(edges);
  std::vector<Eigen::Vector3d> logs(static_cast<size_t>(face_count));
  std::vector<char> assigned(static_cast<size_t>(face_count), 0);
  std::queue<int> pending;
  const auto principal = [&](int f) {
    const Eigen::AngleAxisd& r = rotations[static_cast<size_t>(f)];
    return Eigen::Vector3d(r.angle() * r.axis());
  };
  const auto assign_from_neighbours = [&](int face) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    int count = 0;
    for (int corner = 0; corner < 3; ++corner) {
      for (int neighbour : faces_of_edge[edges.face_edges(face, corner)]) {
        if (neighbour == face || !assigned[static_cast<size_t>(neighbour)]) continue;
        mean += logs[static_cast<size_t>(neighbour)];
        ++count;
      }
    }
    const Eigen::AngleAxisd& r = rotations[static_cast<size_t>(face)];
    const Eigen::Vector3d first = r.angle() * r.axis();
    const Eigen::Vector3d second = (r.angle() - 2.0 * kPi) * r.axis();
    if (count > 0) mean /= count;
    logs[static_cast<size_t>(face)] =
        count == 0 || (first - mean).squaredNorm() <= (second - mean).squaredNorm() ? first : second;
    assigned[static_cast<size_t>(face)] = 1;
  };
  const auto spread = [&]() {
    while (!pending.empty()) {
      const int face = pending.front();
      pending.pop();
      for (int corner = 0; corner < 3; ++corner) {
        for (int neighbour : faces_of_edge[edges.face_edges(face, corner)]) {
          if (assigned[static_cast<size_t>(neighbour)]) continue;
          assign_from_neighbours(neighbour);
          pending.push(neighbour);
        }
      }
    }
  };
  for (int f = 0; f < face_count; ++f) {
    if (rotations[static_cast<size_t>(f)].angle() < kUnambiguousAngle) {
      logs[static_cast<size_t>(f)] = principal(f);
      assigned[static_cast<size_t>(f)] = 1;
      pending.push(f);
    }
  }
  spread();
  // Components rotated by nearly pi everywhere: seed each with its least rotated face.
  for (int f = 0; f < face_count; ++f) {
    if (assigned[static_cast<size_t>(f)]) continue;
    logs[static_cast<size_t>(f)] = principal(f);
    assigned[static_cast<size_t>(f)] = 1;
    pending.push(f);
    spread();
  }
  return logs;
}

}  // namespace

PoissonInterpolator::PoissonInterpolator(const Eigen::MatrixX3d& source, const Eigen::MatrixX3d& target,
                                         const Eigen::MatrixX3i& faces)
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
    // Polar decomposition through the SVD, with the reflection (if any) kept in the stretch.
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(deformation, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Vector3d singular = svd.singularValues();
    Eigen::Matrix3d u = svd.matrixU();
    if ((u * svd.matrixV().transpose()).determinant() < 0.0) {
      u.col(2) *= -1.0;
      singular(2) *= -1.0;
    }
    const Eigen::Matrix3d rotation = u * svd.matrixV().transpose();
    s.stretches[static_cast<size_t>(f)] = svd.matrixV() * singular.asDiagonal() * svd.matrixV().transpose();
    rotations[static_cast<size_t>(f)] = Eigen::AngleAxisd(rotation);
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
