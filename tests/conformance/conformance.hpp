// Backend conformance: every registered backend, operation by operation, against a plain reference
// (reference.hpp) and against analytic truths.
//
// How to add a case
//   1. Open the operation's file: rbf_assembly_test.cpp, rbf_evaluate_test.cpp or rk45_test.cpp.
//   2. Use one of its case structs, or write a new one deriving from ConformanceCase. Its fields
//   are
//      its parameters (sizes, seed, tolerances); name() spells every parameter, because it becomes
//      the test's name: Case/BackendConformance.MatchesReference/<backend>_<name>.
//   3. run(device) builds inputs from the fixed seed, lets the device write its outputs into
//      PaddedBlock / PaddedRows (sentinels around the output, a row stride unequal to the row
//      count), computes the expected values with reference.hpp or a closed form, and checks with
//      expect_near (mixed tolerance, see below), untouched() (the sentinels) and exact comparisons
//      where the answer is exact (phi(0), sizes, statuses, counts).
//   4. Append an instance to the list at the end of that file (rbf_assembly_cases() ...).
// Every case then runs on every backend. Odd sizes (1, 5, 7, 11, 13, 257, 1031) keep work-group
// and vector-width remainders in play; a case may widen its tolerance only with a comment saying
// why.
//
// Tolerance. A backend's value a matches the reference's b when
//     |a - b| <= atol + rtol * max(|b|, magnitude),
// where magnitude (returned by reference.hpp beside every value) is the sum of the absolute sizes
// of the terms that make up b: |w_j| * max(|phi_j|, r_j^2) per center and |p_k pi_k| per polynomial
// term for a field value; max(|phi|, r^2) for a single phi value; |pi_k| for a polynomial column.
//  - Sums (field values): rtol = 1e-12. A backend may sum in any order (vector lanes, work-groups,
//    trees) and may fuse multiply-adds; the error of any summation order of n terms is at most
//    about n * eps * magnitude and typically sqrt(n) * eps * magnitude: 3e-13 and 6e-15 for n =
//    2711. One missing or misplaced term changes b by about magnitude / n, far above 1e-12 *
//    magnitude. The magnitude, not |b| alone, because random weights cancel: |b| can be far below
//    its terms.
//  - Single values (assembly): rtol = 1e-13, a few hundred ulp, for logarithms of different
//    accuracy; against max(|phi|, r^2) because phi's rounding error follows r^2 where phi itself
//    passes through 0 (at r = 1).
// The CPU backend stays below 1% of these bounds. NaN and inf are never within tolerance: a NaN
// must be matched by a NaN and an infinity by the same infinity, whatever the tolerance.
#pragma once

#include <posekit/device.hpp>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace posekit::conformance {

/// One conformance case: a set of parameters for one operation.
class ConformanceCase {
 public:
  virtual ~ConformanceCase() = default;
  /// Letters, digits and '_' only; spells every parameter.
  virtual std::string name() const = 0;
  /// Runs the case on `device`, reporting mismatches through EXPECT_* / ADD_FAILURE.
  virtual void run(Device& device) const = 0;
};

using CaseList = std::vector<std::shared_ptr<const ConformanceCase>>;

/// Prints a case as its name in GoogleTest messages (found through the shared_ptr's argument).
inline void PrintTo(const std::shared_ptr<const ConformanceCase>& test_case, std::ostream* out) {
  *out << test_case->name();
}

CaseList rbf_assembly_cases();  // rbf_assembly_test.cpp
CaseList rbf_evaluate_cases();  // rbf_evaluate_test.cpp
CaseList rk45_cases();          // rk45_test.cpp

/// Absolute and relative parts of the mixed tolerance.
struct Tolerance {
  double absolute = 0.0;
  double relative = 0.0;
};

/// Single phi values (assembly) and polynomial terms.
constexpr Tolerance kEntryTolerance{0.0, 1e-13};
/// Field values: sums over up to a few thousand centers.
constexpr Tolerance kSumTolerance{0.0, 1e-12};

/// Passes when every entry satisfies |a - b| <= atol + rtol * max(|b|, magnitude(i, j)), with
/// NaN matched only by NaN and inf only by the same inf. `magnitude` may be empty (then |b| alone).
/// On failure names the first bad entry and counts all of them.
::testing::AssertionResult expect_near(const Eigen::MatrixXd& actual,
                                       const Eigen::MatrixXd& expected,
                                       const Eigen::MatrixXd& magnitude, Tolerance tolerance);

/// A value the backends never produce, written around outputs to catch stray writes.
inline constexpr double kSentinel = -1.2345678901234567e300;

/// A #rows by #cols output inside a larger matrix filled with kSentinel: `pad` rows above and
/// below, `pad` columns left and right. inner() is what the device writes to.
class PaddedBlock {
 public:
  PaddedBlock(Eigen::Index rows, Eigen::Index cols, Eigen::Index pad = 3);
  Eigen::Ref<Eigen::MatrixXd> inner();
  Eigen::MatrixXd value() const;
  /// Passes when every entry outside inner() still holds the sentinel, bit for bit.
  ::testing::AssertionResult untouched() const;

 private:
  Eigen::MatrixXd storage_;
  Eigen::Index rows_;
  Eigen::Index cols_;
  Eigen::Index pad_;
};

/// #rows by 3 output (values, positions) inside a taller matrix with sentinel rows above and below.
class PaddedRows {
 public:
  /// The inner rows start as `initial` (#rows by 3).
  explicit PaddedRows(const Eigen::MatrixX3d& initial, Eigen::Index pad = 3);
  Eigen::Ref<Eigen::MatrixX3d> inner();
  Eigen::MatrixX3d value() const;
  ::testing::AssertionResult untouched() const;

 private:
  Eigen::MatrixX3d storage_;
  Eigen::Index rows_;
  Eigen::Index pad_;
};

/// #rows by 4 points held inside a taller matrix, so that the device sees a row stride unequal to
/// the row count (Points4 is column-major: each coordinate a column).
class StridedPoints {
 public:
  explicit StridedPoints(const Points4& points, Eigen::Index pad = 2);
  Eigen::Ref<const Points4> view() const;

 private:
  Points4 storage_;
  Eigen::Index rows_;
  Eigen::Index pad_;
};

/// Fixed-seed random inputs.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double low, double high);
  /// #count points: x, y, z uniform in [offset - scale, offset + scale], t in [0, time_scale].
  Points4 points(Eigen::Index count, double scale = 1.0, double offset = 0.0,
                 double time_scale = 1.0);
  /// #count points in the unit ball times [0, 1] (where poses live after normalization).
  Points4 ball_points(Eigen::Index count);
  /// A field on `centers` with weights uniform in [-weight_scale, weight_scale] and polynomial
  /// coefficients uniform in [-polynomial_scale, polynomial_scale].
  RbfField field(const Points4& centers, double weight_scale, double polynomial_scale);

 private:
  std::mt19937_64 engine_;
};

/// Replaces `name`'s characters outside [A-Za-z0-9_] by '_' (test names allow no others).
std::string sanitize_name(const std::string& name);

/// The backends named in POSEKIT_EXPECT_BACKENDS (comma-separated); CI sets it so that a backend
/// that silently went missing fails the run instead of skipping.
std::vector<std::string> expected_backends();

}  // namespace posekit::conformance
