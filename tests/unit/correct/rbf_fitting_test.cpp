// The greedy RBF fit as a whole: convergence on a smooth space-time field with far fewer centers
// than constraints, blocked and full factorization giving the same field, the center budget, and
// bad input.
#include <posekit/rbf_fitting.hpp>

#include <posekit/cpu_device.hpp>
#include <posekit/error.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace posekit {
namespace {

using Eigen::Index;

struct Constraints {
  Points4 positions;
  Eigen::MatrixX3d values;
  double diagonal = 0;  // of the surface at t = 0
};

// A bumpy sphere that turns about a tilted axis while its center swings along a curve: vertex
// positions (x(t), t) and their velocities x'(t) = c'(t) + theta'(t) axis x (x(t) - c(t)) at
// `times` evenly spaced times in [0, 1].
Constraints moving_bumpy_sphere(Index vertices, int times) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, 0.2).normalized();
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  Eigen::MatrixX3d rest(vertices, 3);
  for (Index k = 0; k < vertices; ++k) {
    const double z = 1.0 - 2.0 * (static_cast<double>(k) + 0.5) / static_cast<double>(vertices);
    const double r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d u(r * std::cos(golden * k), r * std::sin(golden * k), z);
    const double radius = 0.6 * (1.0 + 0.15 * std::sin(3.0 * u.x()) * std::cos(2.0 * u.y() + u.z()));
    rest.row(k) = radius * u.transpose();
  }
  Constraints c;
  c.diagonal = (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm();
  c.positions.resize(vertices * times, 4);
  c.values.resize(vertices * times, 3);
  for (int i = 0; i < times; ++i) {
    const double t = times > 1 ? static_cast<double>(i) / (times - 1) : 0.0;
    const Eigen::Vector3d center(0.3 * std::sin(2.0 * t), 0.2 * t * t, 0.1 * std::cos(3.0 * t));
    const Eigen::Vector3d center_velocity(0.6 * std::cos(2.0 * t), 0.4 * t, -0.3 * std::sin(3.0 * t));
    const double angle = 0.8 * std::sin(1.3 * t);
    const double angular_speed = 0.8 * 1.3 * std::cos(1.3 * t);
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    for (Index k = 0; k < vertices; ++k) {
      const Index row = i * vertices + k;
      const Eigen::Vector3d offset = rotation * rest.row(k).transpose();
      c.positions.row(row) << (center + offset).transpose(), t;
      c.values.row(row) = (center_velocity + angular_speed * axis.cross(offset)).transpose();
    }
  }
  return c;
}

double max_squared_error(Device& device, const RbfField& field, const Points4& positions,
                         const Eigen::MatrixX3d& values) {
  const std::unique_ptr<DeviceField> uploaded = device.upload_field(field);
  Eigen::MatrixX3d predicted(positions.rows(), 3);
  device.evaluate_rbf(*uploaded, positions, predicted);
  return (predicted - values).rowwise().squaredNorm().maxCoeff();
}

class RbfFitting : public ::testing::Test {
 protected:
  std::unique_ptr<Device> device = make_cpu_device();
};

TEST_F(RbfFitting, ConvergesOnASmoothFieldWithFarFewerCentersThanConstraints) {
  const Constraints c = moving_bumpy_sphere(600, 13);
  RbfFitOptions options;
  options.candidates = 512;
  options.centers_per_round = 64;
  options.max_squared_error = 1e-4 * c.diagonal;
  RbfFitReport report;
  const RbfField field = fit_rbf_field(*device, c.positions, c.values, options, &report);

  ASSERT_TRUE(report.converged) << report.centers << " centers, error " << report.max_squared_error;
  EXPECT_LT(report.max_squared_error, options.max_squared_error);
  EXPECT_EQ(field.centers.rows(), report.centers);
  EXPECT_EQ(field.weights.rows(), report.centers);
  EXPECT_LT(report.centers, c.positions.rows() / 5) << "of " << c.positions.rows() << " constraints";

  const double measured = max_squared_error(*device, field, c.positions, c.values);
  EXPECT_NEAR(measured, report.max_squared_error, 1e-12 + 1e-9 * measured);

  // Every center is one of the constraint positions.
  for (Index j = 0; j < field.centers.rows(); ++j) {
    const Index row = static_cast<Index>(std::lround(field.centers(j, 3) * 12.0)) * 600;
    const auto slice = c.positions.middleRows(row, 600);
    EXPECT_DOUBLE_EQ((slice.rowwise() - field.centers.row(j)).rowwise().squaredNorm().minCoeff(), 0.0)
        << "center " << j;
  }

  ASSERT_FALSE(report.rounds.empty());
  EXPECT_EQ(report.rounds.front().centers, options.centers_per_round);
  for (std::size_t r = 1; r < report.rounds.size(); ++r) {
    EXPECT_GT(report.rounds[r].centers, report.rounds[r - 1].centers);
    EXPECT_LE(report.rounds[r].centers - report.rounds[r - 1].centers, options.centers_per_round);
    EXPECT_GE(report.rounds[r - 1].max_squared_error, options.max_squared_error);
  }
  EXPECT_EQ(report.rounds.back().centers, report.centers);
  EXPECT_EQ(report.rounds.back().max_squared_error, report.max_squared_error);
  for (const RbfFitRound& round : report.rounds) {
    EXPECT_GE(round.assembly_seconds, 0.0);
    EXPECT_GE(round.factorization_seconds, 0.0);
    EXPECT_GE(round.evaluation_seconds, 0.0);
  }
}

TEST_F(RbfFitting, RefitInterpolatesNewValuesAtTheSameCenters) {
  const Constraints c = moving_bumpy_sphere(250, 13);
  RbfFitOptions options;
  options.candidates = 256;
  options.centers_per_round = 32;
  options.max_squared_error = 1e-5 * c.diagonal;
  const RbfFit fit(*device, c.positions, c.values, options);
  const RbfField same = fit.refit(c.values);
  EXPECT_LT((same.weights - fit.field().weights).cwiseAbs().maxCoeff(),
            1e-12 * fit.field().weights.cwiseAbs().maxCoeff());

  // A constant added to every value is a polynomial term: the refit is exact everywhere.
  const Eigen::RowVector3d shift(0.25, -0.5, 0.125);
  const Eigen::MatrixX3d shifted = c.values.rowwise() + shift;
  const RbfField moved = fit.refit(shifted);
  ASSERT_EQ(moved.centers.rows(), fit.field().centers.rows());
  EXPECT_LT((moved.weights - fit.field().weights).cwiseAbs().maxCoeff(),
            1e-9 * fit.field().weights.cwiseAbs().maxCoeff());
  EXPECT_NEAR(max_squared_error(*device, moved, c.positions, shifted), fit.report().max_squared_error,
              1e-9 + 1e-6 * fit.report().max_squared_error);
  for (const Eigen::Index row : fit.center_rows()) ASSERT_LT(row, c.positions.rows());
  EXPECT_THROW(fit.refit(c.values.topRows(10)), ArgumentError);
}

TEST_F(RbfFitting, BlockedAndFullFactorizationGiveTheSameField) {
  const Constraints c = moving_bumpy_sphere(250, 13);
  RbfFitOptions options;
  options.candidates = 256;
  options.centers_per_round = 32;
  options.max_squared_error = 1e-5 * c.diagonal;
  RbfFitReport blocked_report;
  RbfFitReport full_report;
  options.blocked_update = true;
  const RbfField blocked = fit_rbf_field(*device, c.positions, c.values, options, &blocked_report);
  options.blocked_update = false;
  const RbfField full = fit_rbf_field(*device, c.positions, c.values, options, &full_report);

  ASSERT_GE(blocked_report.rounds.size(), 3u);
  ASSERT_EQ(blocked_report.rounds.size(), full_report.rounds.size());
  ASSERT_EQ(blocked.centers, full.centers);
  const double scale = full.weights.cwiseAbs().maxCoeff();
  EXPECT_LT((blocked.weights - full.weights).cwiseAbs().maxCoeff(), 1e-8 * scale);
  EXPECT_LT((blocked.polynomial - full.polynomial).cwiseAbs().maxCoeff(),
            1e-8 * full.polynomial.cwiseAbs().maxCoeff());
  for (std::size_t r = 0; r < full_report.rounds.size(); ++r) {
    EXPECT_NEAR(blocked_report.rounds[r].max_squared_error, full_report.rounds[r].max_squared_error,
                1e-6 * full_report.rounds[r].max_squared_error)
        << "round " << r;
  }
}

TEST_F(RbfFitting, StopsAtTheCenterBudgetWithoutConverging) {
  const Constraints c = moving_bumpy_sphere(300, 13);
  RbfFitOptions options;
  options.candidates = 64;
  options.centers_per_round = 16;
  options.max_squared_error = 1e-9;
  options.max_centers = 45;
  RbfFitReport report;
  const RbfField field = fit_rbf_field(*device, c.positions, c.values, options, &report);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.centers, 45);
  EXPECT_EQ(field.centers.rows(), 45);
  // 20 centers first (the smallest first batch), then 16 and the 9 left in the budget.
  ASSERT_EQ(report.rounds.size(), 3u);
  EXPECT_EQ(report.rounds[0].centers, 20);
  EXPECT_EQ(report.rounds[1].centers, 36);
  EXPECT_GE(report.max_squared_error, options.max_squared_error);
  EXPECT_NEAR(max_squared_error(*device, field, c.positions, c.values), report.max_squared_error,
              1e-9 * report.max_squared_error);
}

// Each of a few constraints is repeated with another value: no field can meet both, and no
// second center may sit on the first. The fit meets every other constraint and says it did not
// converge.
TEST_F(RbfFitting, ConflictingRepeatedConstraintsEndTheFitWithoutConverging) {
  const Constraints c = moving_bumpy_sphere(200, 13);
  const Index count = c.positions.rows();
  const Index repeated = 5;
  Points4 positions(count + repeated, 4);
  Eigen::MatrixX3d values(count + repeated, 3);
  positions.topRows(count) = c.positions;
  values.topRows(count) = c.values;
  for (Index k = 0; k < repeated; ++k) {
    positions.row(count + k) = c.positions.row(k * 311);
    values.row(count + k) = c.values.row(k * 311).array() + 0.5;
  }
  RbfFitOptions options;
  options.candidates = 256;
  options.centers_per_round = 32;
  options.max_squared_error = 1e-4 * c.diagonal;
  RbfFitReport report;
  const RbfField field = fit_rbf_field(*device, positions, values, options, &report);
  EXPECT_FALSE(report.converged);
  EXPECT_NEAR(report.max_squared_error, 0.75, 0.01);

  const std::unique_ptr<DeviceField> uploaded = device->upload_field(field);
  Eigen::MatrixX3d predicted(positions.rows(), 3);
  device->evaluate_rbf(*uploaded, positions, predicted);
  const Eigen::VectorXd errors = (predicted - values).rowwise().squaredNorm();
  for (Index i = 0; i < count; ++i) {
    const bool conflicting = i % 311 == 0 && i / 311 < repeated;
    if (!conflicting) {
      EXPECT_LT(errors(i), options.max_squared_error) << "constraint " << i;
    }
  }
}

TEST_F(RbfFitting, ConstraintsAtOneTimeMakeASingularSystem) {
  Constraints c = moving_bumpy_sphere(300, 1);
  c.positions.col(3).setConstant(0.5);
  try {
    fit_rbf_field(*device, c.positions, c.values, RbfFitOptions{});
    FAIL() << "constraints at one time were fitted";
  } catch (const ArgumentError& error) {
    FAIL() << "not an argument error: " << error.what();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("one time"), std::string::npos) << error.what();
  }
}

// Runs the fit and returns the ArgumentError message, or "" when none was thrown.
std::string argument_error(Device& device, const Points4& positions, const Eigen::MatrixX3d& values,
                           const RbfFitOptions& options) {
  try {
    fit_rbf_field(device, positions, values, options);
  } catch (const ArgumentError& error) {
    return error.what();
  }
  return "";
}

TEST_F(RbfFitting, RejectsOptionsOutOfRangeNamingTheOption) {
  const Constraints c = moving_bumpy_sphere(20, 3);
  struct Case {
    const char* option;
    RbfFitOptions options;
  };
  std::vector<Case> cases;
  RbfFitOptions o;
  o.centers_per_round = 0;
  cases.push_back({"centers_per_round", o});
  o = {};
  o.candidates = 100;  // fewer than the 128 centers per round
  cases.push_back({"candidates", o});
  o = {};
  o.max_squared_error = 0.0;
  cases.push_back({"max_squared_error", o});
  o.max_squared_error = -1.0;
  cases.push_back({"max_squared_error", o});
  o.max_squared_error = std::numeric_limits<double>::quiet_NaN();
  cases.push_back({"max_squared_error", o});
  o.max_squared_error = std::numeric_limits<double>::infinity();
  cases.push_back({"max_squared_error", o});
  o = {};
  o.max_centers = 16;
  cases.push_back({"max_centers", o});
  for (const Case& test : cases) {
    const std::string message = argument_error(*device, c.positions, c.values, test.options);
    EXPECT_NE(message.find(test.option), std::string::npos) << test.option << ": '" << message << "'";
  }
}

TEST_F(RbfFitting, RejectsMismatchedNonFiniteOrTooFewConstraints) {
  const Constraints c = moving_bumpy_sphere(20, 3);
  const RbfFitOptions options;
  EXPECT_NE(argument_error(*device, c.positions, c.values.topRows(59), options).find("59"),
            std::string::npos);

  Eigen::MatrixX3d values = c.values;
  values(17, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(argument_error(*device, c.positions, values, options).find("values row 17"),
            std::string::npos);

  Points4 positions = c.positions;
  positions(33, 3) = std::numeric_limits<double>::infinity();
  EXPECT_NE(argument_error(*device, positions, c.values, options).find("positions row 33"),
            std::string::npos);

  EXPECT_NE(argument_error(*device, c.positions.topRows(19), c.values.topRows(19), options)
                .find("too few"),
            std::string::npos);
}

}  // namespace
}  // namespace posekit
