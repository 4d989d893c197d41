// The RBF interpolation system [[Phi, Pi], [Pi^T, 0]] [W; U] = [V; 0] over a growing set of centers,
// and its factorization: a symmetric block LDL^T extended blockwise as centers arrive (the bordering
// update of the method's section 4.2), or an LU recomputed whole for comparison.
#pragma once

#include <posekit/device.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <cstddef>
#include <vector>

namespace posekit::detail {

/// Block LDL^T factorization A = L D L^T of a symmetric matrix A that grows by bordering: L is unit
/// lower block triangular and D block diagonal, one block per append, each kept as an LU with
/// partial pivoting (the blocks may be indefinite). Appending costs one triangular solve with L.
class BorderedBlockLdlt {
 public:
  /// max_size: the largest size the matrix will reach (capacity never grows beyond it), or 0 when
  /// not known in advance.
  explicit BorderedBlockLdlt(Eigen::Index max_size = 0);

  /// Current size N of A.
  Eigen::Index size() const { return size_; }
  /// Number of diagonal blocks of D (one per non-empty append).
  Eigen::Index block_count() const { return static_cast<Eigen::Index>(block_starts_.size()); }

  /// Extends A (N by N) to [[A, bottom^T], [bottom, corner]]: `bottom` is m by N and `corner` is
  /// m by m and symmetric (only its lower triangle is read). Returns the smallest |pivot| of the new
  /// block of D divided by the largest |entry| of the whole matrix so far (0 when a pivot is exactly
  /// zero; such a factorization must not be used for solving).
  double append(const Eigen::Ref<const Eigen::MatrixXd>& bottom,
                const Eigen::Ref<const Eigen::MatrixXd>& corner);

  /// Solves A X = rhs for N by k `rhs`.
  Eigen::MatrixXd solve(const Eigen::Ref<const Eigen::MatrixXd>& rhs) const;

  /// The factors as dense N by N matrices, for checks (each call copies O(N^2) entries).
  Eigen::MatrixXd unit_lower() const;
  Eigen::MatrixXd block_diagonal() const;

 private:
  void reserve(Eigen::Index size);
  Eigen::Index block_size(std::size_t block) const;
  // Overwrites `block_rows` (the rows of diagonal block `block`, any number of columns) with
  // D_block^-1 times them.
  void solve_diagonal_block(std::size_t block, Eigen::Ref<Eigen::MatrixXd> block_rows) const;

  // capacity by capacity, stored by block rows: block row k holds L's blocks left of the diagonal
  // and the packed LU of D_k (unit lower L_k, upper U_k, with the row order below) on it. The part
  // above the diagonal blocks is unused.
  Eigen::MatrixXd factors_;
  std::vector<Eigen::Index> block_starts_;  // first row of each diagonal block
  // Row i of L_k U_k is row row_order_[i] of D_k (rows numbered as in A; pivoting stays in a block).
  std::vector<Eigen::Index> row_order_;
  Eigen::Index size_ = 0;
  Eigen::Index max_size_ = 0;
  double largest_entry_ = 0;
};

/// Seconds spent by one RbfSystem::add_centers.
struct RbfSystemTimes {
  double assembly = 0;
  double factorization = 0;
};

/// The saddle-point system of the RBF interpolant over its centers, factorized after every
/// add_centers. Blocked mode orders unknowns by insertion, [first batch, 15 polynomial terms,
/// batch 2, batch 3, ...] (a symmetric permutation of [[Phi, Pi], [Pi^T, 0]], same solution), so
/// each batch borders the factorization; full mode assembles and factorizes the whole system.
class RbfSystem {
 public:
  /// Blocks are assembled on `device`, which must outlive the system. max_centers bounds the
  /// storage reserved for the factorization (0: unknown).
  RbfSystem(Device& device, bool blocked_update, Eigen::Index max_centers = 0);

  /// Appends #M by 4 `new_centers` and brings the factorization up to date. Throws ArgumentError
  /// for an empty or non-finite batch, and Error when the system turns (numerically) singular:
  /// fewer than 15 centers in the first batch, repeated centers, or centers on a quadric of R^4;
  /// after such an Error the system must not be used any more.
  RbfSystemTimes add_centers(const Points4& new_centers);

  /// The field interpolating `center_values` (#C by 3, one row per center in insertion order).
  /// Throws Error when the solution is not finite.
  RbfField solve(const Eigen::Ref<const Eigen::MatrixX3d>& center_values) const;

  /// #C by 4 centers in insertion order.
  const Points4& centers() const { return centers_; }
  Eigen::Index center_count() const { return centers_.rows(); }
  bool blocked_update() const { return blocked_; }

 private:
  // Both return the smallest relative pivot of what they factorized (see BorderedBlockLdlt::append).
  // block: the new centers' rows [phi to every center..., 15 polynomial terms].
  double extend_blocked(const Eigen::MatrixXd& block, Eigen::Index old_count);
  // block: every center's row [phi to every center..., 15 polynomial terms].
  double refactorize_full(const Eigen::MatrixXd& block);

  Device* device_;
  bool blocked_;
  Eigen::Index max_centers_;
  Points4 centers_;
  Eigen::Index first_batch_ = 0;  // blocked mode: the polynomial unknowns follow this many centers
  BorderedBlockLdlt bordered_;                 // blocked mode
  Eigen::PartialPivLU<Eigen::MatrixXd> full_;  // full mode
};

}  // namespace posekit::detail
