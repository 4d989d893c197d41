#include "interpolate/sparse_cholesky.hpp"

#include "interpolate/serialized_openmp.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

namespace posekit::interpolation {

struct SparseCholesky::Factorization {
  explicit Factorization(Eigen::Index rows) : cholmod_rows(rows) {
    // Failures come back through factorize(); CHOLMOD would print them to stdout.
    cholmod.cholmod().print = 0;
  }
  Eigen::Index cholmod_rows;
  bool use_cholmod = false;
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> cholmod;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> simplicial;
};

SparseCholesky::SparseCholesky(Eigen::Index cholmod_rows)
    : factorization_(std::make_unique<Factorization>(cholmod_rows)) {}

SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze_pattern(const Eigen::SparseMatrix<double>& matrix) {
  Factorization& f = *factorization_;
  f.use_cholmod = matrix.rows() >= f.cholmod_rows;
  if (f.use_cholmod) {
    const SerializedOpenMpRegions serialized;
    f.cholmod.analyzePattern(matrix);
  } else {
    f.simplicial.analyzePattern(matrix);
  }
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& matrix) {
  Factorization& f = *factorization_;
  if (f.use_cholmod) {
    const SerializedOpenMpRegions serialized;
    f.cholmod.factorize(matrix);
    return f.cholmod.info() == Eigen::Success;
  }
  f.simplicial.factorize(matrix);
  return f.simplicial.info() == Eigen::Success;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  const Factorization& f = *factorization_;
  if (!f.use_cholmod) return f.simplicial.solve(rhs);
  const SerializedOpenMpRegions serialized;
  return f.cholmod.solve(rhs);
}

bool SparseCholesky::uses_cholmod() const { return factorization_->use_cholmod; }

}  // namespace posekit::interpolation
