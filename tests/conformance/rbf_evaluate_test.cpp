// Conformance cases of Device::upload_field + Device::evaluate_rbf; conformance.hpp says how to add
// one.
#include "conformance.hpp"
#include "reference.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace posekit::conformance {
namespace {

// A random field (weights and polynomial coefficients uniform in +-weight_scale and
// +-polynomial_scale) evaluated at random points. The first `on_center` points sit exactly on
// centers; the last `nan_rows` points have a NaN coordinate, whose rows must come out NaN while
// the others stay finite. The field is uploaded once and evaluated twice, the second time at the
// points in reverse order: a value may not depend on where its point sits in the batch.
struct RbfEvaluateCase final : ConformanceCase {
  Eigen::Index points = 0;
  Eigen::Index centers = 0;
  std::uint64_t seed = 1;
  double weight_scale = 1.0;
  double polynomial_scale = 1.0;
  Eigen::Index on_center = 0;
  Eigen::Index nan_rows = 0;
  double offset = 0.0;
  double scale = 1.0;
  double time_scale = 1.0;
  Tolerance tolerance = kSumTolerance;


  std::string name() const override {
    std::ostringstream name;
    name << "evaluate_points" << points << "_centers" << centers << "_seed" << seed;
    if (weight_scale != 1.0) name << "_weights" << weight_scale;
    if (polynomial_scale != 1.0) name << "_polynomial" << polynomial_scale;
    if (on_center > 0) name << "_on_center" << on_center;
    if (nan_rows > 0) name << "_nan_rows" << nan_rows;
    if (offset != 0.0) name << "_offset" << offset;
    if (scale != 1.0) name << "_scale" << scale;
    if (time_scale != 1.0) name << "_time_scale" << time_scale;
    return sanitize_name(name.str());
  }

  void run(Device& device) const override {
    Random random(seed);
    const Points4 center_set = random.points(centers, scale, offset, time_scale);
    const RbfField field = random.field(center_set, weight_scale, polynomial_scale);
    Points4 point_set = random.points(points, scale, offset, time_scale);
    const Eigen::Index coinciding = std::min({on_center, points, centers});
    for (Eigen::Index i = 0; i < coinciding; ++i) point_set.row(i) = center_set.row(i);
    for (Eigen::Index r = 0; r < std::min(nan_rows, points); ++r) {
      point_set(points - 1 - r, r % 4) = std::numeric_limits<double>::quiet_NaN();
    }
    const reference::Evaluation expected = reference::evaluate(field, point_set);

    const std::unique_ptr<DeviceField> uploaded = device.upload_field(field);
    EXPECT_EQ(uploaded->center_count(), centers);

    const StridedPoints input(point_set);
    PaddedRows output(Eigen::MatrixX3d::Zero(points, 3));
    device.evaluate_rbf(*uploaded, input.view(), output.inner());
    EXPECT_TRUE(output.untouched());
    EXPECT_TRUE(expect_near(output.value(), expected.values, expected.magnitude, tolerance));

    const Points4 reversed = point_set.colwise().reverse();
    PaddedRows reversed_output(Eigen::MatrixX3d::Zero(points, 3));
    device.evaluate_rbf(*uploaded, StridedPoints(reversed).view(), reversed_output.inner());
    EXPECT_TRUE(reversed_output.untouched());
    const Eigen::MatrixXd reversed_expected = expected.values.colwise().reverse();
    const Eigen::MatrixXd reversed_magnitude = expected.magnitude.colwise().reverse();
    EXPECT_TRUE(
        expect_near(reversed_output.value(), reversed_expected, reversed_magnitude, tolerance))
        << "second evaluation, points in reverse order";
  }
};

std::shared_ptr<const ConformanceCase> evaluate(Eigen::Index points, Eigen::Index centers,
                                                std::uint64_t seed) {
  auto c = std::make_shared<RbfEvaluateCase>();
  c->points = points;
  c->centers = centers;
  c->seed = seed;
  return c;
}

}  // namespace

CaseList rbf_evaluate_cases() {
  CaseList cases = {
      evaluate(0, 5, 1),
      evaluate(1, 1, 2),
      evaluate(5, 7, 3),
      evaluate(7, 0, 4),
      evaluate(11, 13, 5),
      evaluate(13, 1, 6),
      evaluate(257, 11, 7),
      evaluate(1031, 257, 8),
      evaluate(129, 2711, 9),
      evaluate(1, 2711, 10),
      evaluate(0, 0, 11),
      evaluate(20011, 7, 17),  // a batch large enough to be split across threads / dispatches
  };

  auto on_center = std::make_shared<RbfEvaluateCase>();
  on_center->points = 13;
  on_center->centers = 11;
  on_center->seed = 12;
  on_center->on_center = 5;
  cases.push_back(on_center);

  auto polynomial_only = std::make_shared<RbfEvaluateCase>();
  polynomial_only->points = 257;
  polynomial_only->centers = 0;
  polynomial_only->seed = 13;
  polynomial_only->polynomial_scale = 10.0;
  cases.push_back(polynomial_only);

  auto far_and_close = std::make_shared<RbfEvaluateCase>();
  far_and_close->points = 257;
  far_and_close->centers = 13;
  far_and_close->seed = 14;
  far_and_close->offset = 1e3;
  far_and_close->scale = 1e-2;
  far_and_close->time_scale = 1e-2;
  far_and_close->polynomial_scale = 0.0;
  cases.push_back(far_and_close);

  auto wide = std::make_shared<RbfEvaluateCase>();
  wide->points = 31;
  wide->centers = 129;
  wide->seed = 15;
  wide->scale = 1e2;
  wide->weight_scale = 1e-3;
  cases.push_back(wide);

  auto with_nan = std::make_shared<RbfEvaluateCase>();
  with_nan->points = 11;
  with_nan->centers = 7;
  with_nan->seed = 16;
  with_nan->nan_rows = 2;
  cases.push_back(with_nan);
  return cases;
}

}  // namespace posekit::conformance
