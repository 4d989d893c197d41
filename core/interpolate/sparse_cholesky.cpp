#include "interpolate/sparse_cholesky.hpp"

#include "interpolate/serialized_openmp.hpp"

#include <posekit/error.hpp>

#include <Eigen/SparseCholesky>
#include <cholmod.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace posekit::interpolation {
namespace {

// CHOLMOD's view of the lower triangle of a compressed column-major matrix (its upper entries are
// ignored), as Eigen's CHOLMOD wrapper makes it.
cholmod_sparse lower_triangle_view(const Eigen::SparseMatrix<double>& matrix) {
  cholmod_sparse view{};
  view.nrow = static_cast<size_t>(matrix.rows());
  view.ncol = static_cast<size_t>(matrix.cols());
  view.nzmax = static_cast<size_t>(matrix.nonZeros());
  view.p = const_cast<int*>(matrix.outerIndexPtr());
  view.i = const_cast<int*>(matrix.innerIndexPtr());
  view.x = const_cast<double*>(matrix.valuePtr());
  view.stype = -1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

// Asks the kernel to back the untouched memory at `data` with huge pages where it can: a whole mesh's
// supernodal factor takes hundreds of megabytes, and touching them first a small page at a time cost
// more than a refactorization (docs/interpolate.md, "Speed"). Only advice: it changes no value.
void advise_huge_pages(void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto begin = (reinterpret_cast<uintptr_t>(data) + page - 1) / page * page;
  const auto end = (reinterpret_cast<uintptr_t>(data) + bytes) / page * page;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace

struct SparseCholesky::Factorization {
  explicit Factorization(Eigen::Index rows) : cholmod_rows(rows) {
    cholmod_start(&common);
    // Eigen's automatic mode: CHOLMOD picks supernodal or simplicial and leaves the factor as it is.
    common.final_asis = 1;
    common.supernodal = CHOLMOD_AUTO;
    // Failures come back through factorize(); CHOLMOD would print them to stdout.
    common.print = 0;
  }
  ~Factorization() {
    release();
    cholmod_finish(&common);
  }
  Factorization(const Factorization&) = delete;
  Factorization& operator=(const Factorization&) = delete;

  void release() {
    cholmod_free_sparse(&permuted_lower, &common);
    cholmod_free_factor(&factor, &common);
    value_sources.clear();
  }

  // The pattern of tril(P A P') for the factor's permutation P, with the position in the caller's
  // value array that every entry takes its value from: the entry of A's lower triangle that lands
  // there, as CHOLMOD's own permuted transposes would move it. Written straight into the final
  // arrays: on a whole mesh they hold millions of entries, and fresh memory is slow to touch.
  void prepare_permuted_lower(const Eigen::SparseMatrix<double>& matrix) {
    const int n = static_cast<int>(matrix.rows());
    const int* perm = static_cast<const int*>(factor->Perm);
    std::vector<int> inverse(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) inverse[static_cast<size_t>(perm[k])] = k;
    const int* outer = matrix.outerIndexPtr();
    const int* inner = matrix.innerIndexPtr();
    // Calls place(row, column, source) for every lower entry of A at its place in P A P'.
    const auto for_each_entry = [&](auto place) {
      for (int c = 0; c < n; ++c) {
        const int j = inverse[static_cast<size_t>(c)];
        for (int k = outer[c]; k < outer[c + 1]; ++k) {
          if (inner[k] < c) continue;  // upper triangle: CHOLMOD reads the lower one
          const int i = inverse[static_cast<size_t>(inner[k])];
          place(std::max(i, j), std::min(i, j), k);
        }
      }
    };
    std::vector<int> next(static_cast<size_t>(n) + 1, 0);
    for_each_entry([&](int, int column, int) { ++next[static_cast<size_t>(column) + 1]; });
    for (int k = 0; k < n; ++k) next[static_cast<size_t>(k) + 1] += next[static_cast<size_t>(k)];
    const auto count = static_cast<size_t>(next[static_cast<size_t>(n)]);
    permuted_lower = cholmod_allocate_sparse(static_cast<size_t>(n), static_cast<size_t>(n), count, 1, 1, -1,
                                             CHOLMOD_REAL, &common);
    if (permuted_lower == nullptr) throw Error("sparse Cholesky: out of memory for the permuted matrix");
    int* column_starts = static_cast<int*>(permuted_lower->p);
    std::copy(next.begin(), next.end(), column_starts);
    int* rows = static_cast<int*>(permuted_lower->i);
    value_sources.resize(count);
    for_each_entry([&](int row, int column, int source) {
      const auto at = static_cast<size_t>(next[static_cast<size_t>(column)]++);
      rows[at] = row;
      value_sources[at] = source;
    });
    // Rows ascending in every column (a few dozen entries each), as CHOLMOD's transposes leave them.
    for (int c = 0; c < n; ++c) {
      for (int k = column_starts[c] + 1; k < column_starts[c + 1]; ++k) {
        const int row = rows[k];
        const int source = value_sources[static_cast<size_t>(k)];
        int at = k;
        for (; at > column_starts[c] && rows[at - 1] > row; --at) {
          rows[at] = rows[at - 1];
          value_sources[static_cast<size_t>(at)] = value_sources[static_cast<size_t>(at) - 1];
        }
        rows[at] = row;
        value_sources[static_cast<size_t>(at)] = source;
      }
    }
  }

  Eigen::Index cholmod_rows;
  bool use_cholmod = false;
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  Eigen::Index analyzed_nonzeros = 0;
  cholmod_sparse* permuted_lower = nullptr;  // supernodal factors only
  std::vector<int> value_sources;            // per entry of permuted_lower
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> simplicial;
};

SparseCholesky::SparseCholesky(Eigen::Index cholmod_rows)
    : factorization_(std::make_unique<Factorization>(cholmod_rows)) {}

SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze_pattern(const Eigen::SparseMatrix<double>& matrix) {
  Factorization& f = *factorization_;
  f.use_cholmod = matrix.rows() >= f.cholmod_rows;
  if (!f.use_cholmod) {
    f.simplicial.analyzePattern(matrix);
    return;
  }
  if (!matrix.isCompressed()) throw Error("sparse Cholesky: the matrix is not compressed");
  if (matrix.rows() != matrix.cols()) throw Error("sparse Cholesky: the matrix is not square");
  const SerializedOpenMpRegions serialized;
  f.release();
  cholmod_sparse view = lower_triangle_view(matrix);
  f.factor = cholmod_analyze(&view, &f.common);
  f.analyzed_nonzeros = matrix.nonZeros();
  if (f.factor == nullptr) throw Error("sparse Cholesky: CHOLMOD's analysis failed");
  if (!f.factor->is_super) return;
  f.prepare_permuted_lower(matrix);
  // The factor's values are allocated here rather than in the first factorization, untouched, so that
  // they can be advised first.
  if (!cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, f.factor, &f.common)) {
    throw Error("sparse Cholesky: out of memory for the factor");
  }
  advise_huge_pages(f.factor->x, f.factor->xsize * sizeof(double));
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& matrix) {
  Factorization& f = *factorization_;
  if (!f.use_cholmod) {
    f.simplicial.factorize(matrix);
    return f.simplicial.info() == Eigen::Success;
  }
  if (f.factor == nullptr) return false;  // no analysis yet
  if (!matrix.isCompressed() || matrix.nonZeros() != f.analyzed_nonzeros) {
    throw Error("sparse Cholesky: the matrix does not have the analyzed pattern");
  }
  const SerializedOpenMpRegions serialized;
  double no_shift[2] = {0.0, 0.0};
  int done = 0;
  if (f.permuted_lower != nullptr) {
    const double* values = matrix.valuePtr();
    auto* permuted = static_cast<double*>(f.permuted_lower->x);
    for (size_t k = 0; k < f.value_sources.size(); ++k) permuted[k] = values[f.value_sources[k]];
    done = cholmod_super_numeric(f.permuted_lower, nullptr, no_shift, f.factor, &f.common);
  } else {
    cholmod_sparse view = lower_triangle_view(matrix);
    done = cholmod_factorize_p(&view, no_shift, nullptr, 0, f.factor, &f.common);
  }
  // A pivot that is not positive leaves `minor` at its column.
  return done != 0 && f.factor->minor == f.factor->n;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  Factorization& f = *factorization_;
  if (!f.use_cholmod) return f.simplicial.solve(rhs);
  const SerializedOpenMpRegions serialized;
  cholmod_dense right{};
  right.nrow = static_cast<size_t>(rhs.size());
  right.ncol = 1;
  right.nzmax = static_cast<size_t>(rhs.size());
  right.d = static_cast<size_t>(rhs.size());
  right.x = const_cast<double*>(rhs.data());
  right.xtype = CHOLMOD_REAL;
  right.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* solution = cholmod_solve(CHOLMOD_A, f.factor, &right, &f.common);
  if (solution == nullptr) return Eigen::VectorXd::Constant(rhs.size(), std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(solution->x), rhs.size());
  cholmod_free_dense(&solution, &f.common);
  return x;
}

bool SparseCholesky::uses_cholmod() const { return factorization_->use_cholmod; }

bool SparseCholesky::factorizes_supernodally() const {
  const Factorization& f = *factorization_;
  return f.use_cholmod && f.factor != nullptr && f.factor->is_super != 0;
}

}  // namespace posekit::interpolation
