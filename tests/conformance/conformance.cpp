#include "conformance.hpp"

#include <posekit/device_registry.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace posekit::conformance {
namespace {

bool same_bits(double a, double b) {
  std::uint64_t a_bits = 0;
  std::uint64_t b_bits = 0;
  std::memcpy(&a_bits, &a, sizeof a);
  std::memcpy(&b_bits, &b, sizeof b);
  return a_bits == b_bits;
}

// NaN only matches NaN, an infinity only the same infinity; finite values go by the tolerance.
bool within(double actual, double expected, double scale, Tolerance tolerance) {
  if (std::isnan(actual) || std::isnan(expected)) return std::isnan(actual) && std::isnan(expected);
  if (std::isinf(actual) || std::isinf(expected)) return actual == expected;
  return std::abs(actual - expected) <= tolerance.absolute + tolerance.relative * scale;
}

}  // namespace

::testing::AssertionResult expect_near(const Eigen::MatrixXd& actual,
                                       const Eigen::MatrixXd& expected,
                                       const Eigen::MatrixXd& magnitude, Tolerance tolerance) {
  if (actual.rows() != expected.rows() || actual.cols() != expected.cols()) {
    return ::testing::AssertionFailure()
           << "size " << actual.rows() << " by " << actual.cols() << " differs from the expected "
           << expected.rows() << " by " << expected.cols();
  }
  const bool has_magnitude = magnitude.size() != 0;
  long long mismatches = 0;
  std::ostringstream first;
  for (Eigen::Index j = 0; j < actual.cols(); ++j) {
    for (Eigen::Index i = 0; i < actual.rows(); ++i) {
      const double a = actual(i, j);
      const double b = expected(i, j);
      const double scale = std::max(std::abs(b), has_magnitude ? magnitude(i, j) : 0.0);
      if (within(a, b, scale, tolerance)) continue;
      if (mismatches == 0) {
        first.precision(17);
        first << "first mismatch at (" << i << ", " << j << "): " << a << " vs expected " << b
              << " (difference " << std::abs(a - b) << ", allowed "
              << tolerance.absolute + tolerance.relative * scale << ")";
      }
      ++mismatches;
    }
  }
  if (mismatches == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << mismatches << " of " << actual.size() << " entries out of tolerance; " << first.str();
}

PaddedBlock::PaddedBlock(Eigen::Index rows, Eigen::Index cols, Eigen::Index pad)
    : storage_(Eigen::MatrixXd::Constant(rows + 2 * pad, cols + 2 * pad, kSentinel)),
      rows_(rows),
      cols_(cols),
      pad_(pad) {}

Eigen::Ref<Eigen::MatrixXd> PaddedBlock::inner() {
  return storage_.block(pad_, pad_, rows_, cols_);
}

Eigen::MatrixXd PaddedBlock::value() const { return storage_.block(pad_, pad_, rows_, cols_); }

::testing::AssertionResult PaddedBlock::untouched() const {
  for (Eigen::Index j = 0; j < storage_.cols(); ++j) {
    for (Eigen::Index i = 0; i < storage_.rows(); ++i) {
      const bool inside = i >= pad_ && i < pad_ + rows_ && j >= pad_ && j < pad_ + cols_;
      if (!inside && !same_bits(storage_(i, j), kSentinel)) {
        return ::testing::AssertionFailure()
               << "write outside the output: padding entry (" << i - pad_ << ", " << j - pad_
               << ") relative to the output's first entry holds " << storage_(i, j);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

PaddedRows::PaddedRows(const Eigen::MatrixX3d& initial, Eigen::Index pad)
    : storage_(Eigen::MatrixX3d::Constant(initial.rows() + 2 * pad, 3, kSentinel)),
      rows_(initial.rows()),
      pad_(pad) {
  storage_.middleRows(pad_, rows_) = initial;
}

Eigen::Ref<Eigen::MatrixX3d> PaddedRows::inner() { return storage_.middleRows(pad_, rows_); }

Eigen::MatrixX3d PaddedRows::value() const { return storage_.middleRows(pad_, rows_); }

::testing::AssertionResult PaddedRows::untouched() const {
  for (Eigen::Index j = 0; j < 3; ++j) {
    for (Eigen::Index i = 0; i < storage_.rows(); ++i) {
      const bool inside = i >= pad_ && i < pad_ + rows_;
      if (!inside && !same_bits(storage_(i, j), kSentinel)) {
        return ::testing::AssertionFailure()
               << "write outside the output: padding row " << i - pad_ << " (relative to the first "
               << "output row), column " << j << " holds " << storage_(i, j);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

StridedPoints::StridedPoints(const Points4& points, Eigen::Index pad)
    : storage_(Points4::Constant(points.rows() + 2 * pad, 4, kSentinel)),
      rows_(points.rows()),
      pad_(pad) {
  storage_.middleRows(pad_, rows_) = points;
}

Eigen::Ref<const Points4> StridedPoints::view() const { return storage_.middleRows(pad_, rows_); }

double Random::uniform(double low, double high) {
  return std::uniform_real_distribution<double>(low, high)(engine_);
}

Points4 Random::points(Eigen::Index count, double scale, double offset, double time_scale) {
  Points4 points(count, 4);
  for (Eigen::Index i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) points(i, k) = offset + uniform(-scale, scale);
    points(i, 3) = uniform(0.0, time_scale);
  }
  return points;
}

Points4 Random::ball_points(Eigen::Index count) {
  Points4 points(count, 4);
  for (Eigen::Index i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    do {
      p = Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    } while (p.squaredNorm() > 1.0);
    points.row(i) << p.transpose(), uniform(0.0, 1.0);
  }
  return points;
}

RbfField Random::field(const Points4& centers, double weight_scale, double polynomial_scale) {
  RbfField field;
  field.centers = centers;
  field.weights.resize(centers.rows(), 3);
  for (Eigen::Index i = 0; i < field.weights.size(); ++i) {
    field.weights.data()[i] = uniform(-weight_scale, weight_scale);
  }
  for (Eigen::Index i = 0; i < field.polynomial.size(); ++i) {
    field.polynomial.data()[i] = uniform(-polynomial_scale, polynomial_scale);
  }
  return field;
}

std::string sanitize_name(const std::string& name) {
  std::string result = name;
  for (char& c : result) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!allowed) c = '_';
  }
  return result;
}

std::vector<std::string> expected_backends() {
  const char* variable = std::getenv("POSEKIT_EXPECT_BACKENDS");
  return variable == nullptr ? std::vector<std::string>{} : parse_backend_list(variable);
}

}  // namespace posekit::conformance
