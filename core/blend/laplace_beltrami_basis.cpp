#include <posekit/error.hpp>
#include <posekit/laplace_beltrami.hpp>

#include <Eigen/SparseCholesky>
#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <string>

namespace posekit {
namespace {

// (A - sigma I)^-1 for the symmetric standard form A = M^-1/2 L M^-1/2, by one sparse LDLT.
// Spectra calls set_shift once and perform_op for every Lanczos step.
class ShiftInvertOperator {
 public:
  using Scalar = double;
  explicit ShiftInvertOperator(const Eigen::SparseMatrix<double>& matrix) : matrix_(matrix) {}
  Eigen::Index rows() const { return matrix_.rows(); }
  Eigen::Index cols() const { return matrix_.cols(); }
  void set_shift(double sigma) {
    Eigen::SparseMatrix<double> identity(matrix_.rows(), matrix_.cols());
    identity.setIdentity();
    solver_.compute(matrix_ - sigma * identity);
    if (solver_.info() != Eigen::Success) {
      throw ArgumentError("laplace_beltrami_basis: the shifted Laplacian could not be factorized");
    }
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, matrix_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, matrix_.rows());
    y = solver_.solve(x);
  }

 private:
  const Eigen::SparseMatrix<double>& matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace

LaplaceBeltramiBasis laplace_beltrami_basis(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                            const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                            int count) {
  check_laplace_beltrami_mesh(vertices, faces);
  const int vertex_count = static_cast<int>(vertices.rows());
  if (count < 1 || count >= vertex_count) {
    throw ArgumentError("laplace_beltrami_basis: count is " + std::to_string(count) + "; it must lie in [1, " +
                        std::to_string(vertex_count - 1) + "] for a mesh of " + std::to_string(vertex_count) +
                        " vertices");
  }
  const Eigen::SparseMatrix<double> laplacian = cotangent_laplacian(vertices, faces);
  const Eigen::VectorXd mass = lumped_mass(vertices, faces);
  const Eigen::VectorXd inverse_root = mass.cwiseSqrt().cwiseInverse();
  const Eigen::SparseMatrix<double> standard = inverse_root.asDiagonal() * laplacian * inverse_root.asDiagonal();

  // A shift just below zero keeps A - sigma I positive definite (LDLT without pivoting) while the
  // eigenvalues nearest to it are the wanted smallest ones. It is relative to the mean diagonal,
  // so it does not depend on the mesh's size.
  const double sigma = -1e-3 * standard.diagonal().mean() / vertex_count;
  ShiftInvertOperator op(standard);
  // Lanczos finds repeated eigenvalues (symmetric shapes) late: asking for spare pairs and keeping the
  // smallest `count` catches every copy in practice. Spectra needs requested < ncv <= n.
  const int requested = std::min(vertex_count - 2, count + std::max(10, count / 2));
  const int subspace = std::min(vertex_count, std::max(2 * requested + 1, requested + 20));
  if (count > requested || requested >= subspace) {
    throw ArgumentError("laplace_beltrami_basis: count " + std::to_string(count) + " is too large for a mesh of " +
                        std::to_string(vertex_count) + " vertices");
  }
  Spectra::SymEigsShiftSolver<ShiftInvertOperator> solver(op, requested, subspace, sigma);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 2000, 1e-10, Spectra::SortRule::SmallestAlge);
  if (solver.info() != Spectra::CompInfo::Successful) {
    throw ArgumentError("laplace_beltrami_basis: the eigensolver did not converge for " + std::to_string(count) +
                        " eigenfunctions");
  }
  LaplaceBeltramiBasis basis;
  basis.eigenvalues = solver.eigenvalues().head(count);  // ascending
  basis.eigenfunctions = inverse_root.asDiagonal() * solver.eigenvectors().leftCols(count);
  for (int j = 0; j < count; ++j) {
    Eigen::Index largest = 0;
    basis.eigenfunctions.col(j).cwiseAbs().maxCoeff(&largest);
    if (basis.eigenfunctions(largest, j) < 0.0) basis.eigenfunctions.col(j) *= -1.0;
  }
  // The constant function has eigenvalue 0; round-off may make it a tiny negative number.
  basis.eigenvalues = basis.eigenvalues.cwiseMax(0.0);
  return basis;
}

}  // namespace posekit
