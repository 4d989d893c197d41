// Greedy fitting of an RBF field f: R^4 -> R^3 to scattered constraints f(y_i) = v_i.
//
// Centers are a growing subset of the constraint positions. The first batch starts with the two
// (approximately) most distant constraints and is filled up to `centers_per_round` (at least 20)
// by farthest-point sampling: two centers alone cannot determine the 15 polynomial terms. Each
// round then evaluates the field at every constraint, and while the largest squared error is at
// least the tolerance, adds up to `centers_per_round` centers among the `candidates` worst
// constraints: the worst first, then each next the one farthest from all centers, existing and
// new, which keeps centers from clustering and the system well conditioned. The saddle-point system
// [[Phi, Pi], [Pi^T, 0]] [W; U] = [V; 0] keeps an LU factorization that each round extends by a
// block (only an m by m factorization is new), or refactorizes whole when asked to.
#pragma once

#include <posekit/device.hpp>

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace posekit {

/// Controls of fit_rbf_field(); the defaults are those of the method's authors.
struct RbfFitOptions {
  int candidates = 1024;            ///< p: worst constraints considered per round (>= centers_per_round)
  int centers_per_round = 128;      ///< m: centers added per round (>= 1)
  double max_squared_error = 1e-4;  ///< eps: stop when every |f(y_i) - v_i|^2 < eps (absolute, > 0)
  int max_centers = 30000;          ///< give up (converged = false) at this many centers (>= 17)
  bool blocked_update = true;       ///< false: refactorize the whole system every round
};

/// One round: the field with `centers` centers and how well it fits.
struct RbfFitRound {
  int centers = 0;
  double max_squared_error = 0;     ///< over all constraints
  double assembly_seconds = 0;      ///< building the new rows and columns of the system
  double factorization_seconds = 0; ///< extending (or redoing) the LU factorization and solving
  double evaluation_seconds = 0;    ///< evaluating the field at every constraint
};

/// What fit_rbf_field() did.
struct RbfFitReport {
  std::vector<RbfFitRound> rounds;
  int centers = 0;                  ///< centers of the returned field
  double max_squared_error = 0;     ///< of the returned field over all constraints
  bool converged = false;           ///< max_squared_error < options.max_squared_error
};

/// Fits f(positions_i) = values_i: `positions` is #P by 4 (x, y, z, t), `values` #P by 3. Returns
/// the field of the last round; when max_centers is reached first (or no constraint can be added)
/// the field is returned anyway with report->converged = false. Positions should be of moderate
/// scale (e.g. normalized into the unit sphere): the system is solved in the caller's coordinates.
/// Throws ArgumentError for options out of range, mismatched sizes, non-finite input or fewer than
/// 20 constraints, and Error when the system turns singular (e.g. all constraints at one time).
RbfField fit_rbf_field(Device& device, const Points4& positions, const Eigen::Ref<const Eigen::MatrixX3d>& values,
                       const RbfFitOptions& options, RbfFitReport* report = nullptr);

namespace detail {
class RbfSystem;
}

/// The greedy fit of fit_rbf_field() that keeps its centers and factorization, so that the same
/// centers can interpolate other values at the cost of two triangular solves.
class RbfFit {
 public:
  /// Runs the greedy fit on `device` (which must outlive this object); arguments and exceptions as
  /// for fit_rbf_field().
  RbfFit(Device& device, const Points4& positions, const Eigen::Ref<const Eigen::MatrixX3d>& values,
         const RbfFitOptions& options);
  ~RbfFit();
  RbfFit(RbfFit&&) noexcept;
  RbfFit& operator=(RbfFit&&) noexcept;

  const RbfField& field() const { return field_; }
  const RbfFitReport& report() const { return report_; }
  /// Row of `positions` each center was taken from, in insertion order.
  const std::vector<Eigen::Index>& center_rows() const { return center_rows_; }

  /// The field with the same centers interpolating `values` (#P by 3, one row per constraint, as
  /// `values` of the constructor; only the centers' rows are used). Throws ArgumentError on a size
  /// mismatch and Error when the solution is not finite.
  RbfField refit(const Eigen::Ref<const Eigen::MatrixX3d>& values) const;

 private:
  std::unique_ptr<detail::RbfSystem> system_;
  std::vector<Eigen::Index> center_rows_;
  RbfField field_;
  RbfFitReport report_;
  Eigen::Index constraint_count_ = 0;
};

}  // namespace posekit
