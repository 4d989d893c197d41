// The factorization of the symmetric positive definite systems of the edge-space Gauss-Newton.
// Large systems go to SuiteSparse's CHOLMOD, which factorizes supernodally (dense BLAS kernels on
// blocks of columns) where the factor is dense enough, as on the normal matrix of a whole mesh of
// tens of thousands of vertices: several times faster than a simplicial LDLT there. Small systems
// keep Eigen's simplicial LDLT: CHOLMOD saves at most a fifth of the time on them, and the
// corrections that go through an edge-space pose are sensitive to the last bits of its solution
// (docs/interpolate.md, "Speed"). CHOLMOD's own OpenMP regions run on one thread while it works
// (serialized_openmp.hpp). CHOLMOD's headers stay in the source file.
//
// The pattern is fixed and the values change at every Gauss-Newton iteration, so the supernodal
// path keeps the permuted lower triangle that CHOLMOD factorizes, P A P', and only gathers the new
// values into it: CHOLMOD's own factorization call would build it again with two transposes and
// their allocations every time. The numbers handed to CHOLMOD are the same, and so is the factor.
// The factor's values (hundreds of megabytes on a whole mesh) are allocated with the analysis and
// advised for huge pages before they are first touched.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>

namespace posekit::interpolation {

class SparseCholesky {
 public:
  /// Systems of at least `cholmod_rows` rows are factorized by CHOLMOD, smaller ones by Eigen.
  explicit SparseCholesky(Eigen::Index cholmod_rows = kCholmodRows);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// The symbolic analysis (fill-reducing ordering) of the lower triangle of `matrix`, once per pattern.
  /// A matrix that goes to CHOLMOD is compressed (Eigen's makeCompressed()); throws posekit::Error otherwise.
  void analyze_pattern(const Eigen::SparseMatrix<double>& matrix);

  /// The numeric factorization of `matrix`, whose pattern was analyzed; false where it breaks down
  /// (CHOLMOD: a pivot not positive; the simplicial LDLT: a zero pivot). Throws posekit::Error for
  /// a matrix of CHOLMOD's whose number of stored entries is not the analyzed one's.
  bool factorize(const Eigen::SparseMatrix<double>& matrix);

  /// The solution of matrix * x = rhs with the last factorization; not finite where CHOLMOD fails
  /// (out of memory).
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  /// Whether the analyzed pattern went to CHOLMOD.
  bool uses_cholmod() const;

  /// Whether CHOLMOD's analysis chose a supernodal factor, the path that keeps the permuted matrix.
  bool factorizes_supernodally() const;

  /// 60,000 rows: 20,000 vertices of three coordinates each.
  static constexpr Eigen::Index kCholmodRows = 60000;

 private:
  struct Factorization;
  std::unique_ptr<Factorization> factorization_;
};

}  // namespace posekit::interpolation
