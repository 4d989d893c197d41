// The RBF interpolation system [[Phi, Pi], [Pi^T, 0]] [W; U] = [V; 0] over a growing set of centers,
// and its LU factorization: extended blockwise as centers arrive (the bordering update of the
// method's section 4.2), or recomputed whole for comparison.
#pragma once

#include <posekit/device.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

namespace posekit::detail {

/// LU factorization with partial pivoting, P A = L U, of a square matrix A that grows by bordering:
/// appending [[A, right], [bottom, corner]] computes only T = L^-1 P right, S = bottom U^-1 and the
/// LU of the m by m Schur complement corner - S T, whose row pivoting stays inside the new block
/// (so P is block diagonal). L (unit diagonal, kept below it) and U share one dense matrix whose
/// capacity grows geometrically.
class BorderedLu {
 public:
  /// max_size: the largest size the matrix will reach (capacity never grows beyond it), or 0 when
  /// not known in advance.
  explicit BorderedLu(Eigen::Index max_size = 0);

  /// Current size N of A.
  Eigen::Index size() const { return size_; }

  /// Extends A (N by N) to [[A, right], [bottom, corner]]: `right` is N by m, `bottom` m by N and
  /// `corner` m by m. Returns the smallest |pivot| of the new block divided by the largest |entry|
  /// of the whole matrix so far (0 when a pivot is exactly zero; such a factorization must not be
  /// used for solving).
  double append(const Eigen::Ref<const Eigen::MatrixXd>& right,
                const Eigen::Ref<const Eigen::MatrixXd>& bottom,
                const Eigen::Ref<const Eigen::MatrixXd>& corner);

  /// Solves A X = rhs for N by k `rhs`.
  Eigen::MatrixXd solve(const Eigen::Ref<const Eigen::MatrixXd>& rhs) const;

  /// The factors packed in one N by N matrix: strictly lower part L (unit diagonal), upper part U.
  Eigen::Block<const Eigen::MatrixXd> packed_factors() const {
    return factors_.topLeftCorner(size_, size_);
  }
  /// Row i of L U is row row_order()[i] of A.
  const std::vector<Eigen::Index>& row_order() const { return row_order_; }

 private:
  void reserve(Eigen::Index size);

  Eigen::MatrixXd factors_;  // capacity by capacity; the top-left size_ by size_ block is in use
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
  RbfField solve(const Eigen::MatrixX3d& center_values) const;

  /// #C by 4 centers in insertion order.
  const Points4& centers() const { return centers_; }
  Eigen::Index center_count() const { return centers_.rows(); }
  bool blocked_update() const { return blocked_; }

 private:
  // Both return the smallest relative pivot of what they factorized (see BorderedLu::append).
  // block: the new centers' rows [phi to every center..., 15 polynomial terms].
  double extend_blocked(const Eigen::MatrixXd& block, Eigen::Index old_count);
  // block: every center's row [phi to every center..., 15 polynomial terms].
  double refactorize_full(const Eigen::MatrixXd& block);

  Device* device_;
  bool blocked_;
  Eigen::Index max_centers_;
  Points4 centers_;
  Eigen::Index first_batch_ = 0;  // blocked mode: the polynomial unknowns follow this many centers
  BorderedLu bordered_;                      // blocked mode
  Eigen::PartialPivLU<Eigen::MatrixXd> full_;  // full mode
};

}  // namespace posekit::detail
