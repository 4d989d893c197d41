// Conformance cases of Device::assemble_rbf_block; conformance.hpp says how to add one.
#include "conformance.hpp"
#include "reference.hpp"

#include <algorithm>
#include <sstream>

namespace posekit::conformance {
namespace {

// Random points and centers. The first `on_center` points are copies of centers, where phi(0) = 0
// must come out exactly. `offset` moves everything away from the origin and `scale` / `time_scale`
// set the spread, so that offset 1e3 with a spread of 1e-2 punishes |y|^2 + |c|^2 - 2 y.c.
struct RbfAssemblyCase final : ConformanceCase {
  Eigen::Index points = 0;
  Eigen::Index centers = 0;
  bool with_polynomial = true;
  std::uint64_t seed = 1;
  Eigen::Index on_center = 0;
  double offset = 0.0;
  double scale = 1.0;
  double time_scale = 1.0;
  Tolerance tolerance = kEntryTolerance;


  std::string name() const override {
    std::ostringstream name;
    name << "assembly_points" << points << "_centers" << centers
         << (with_polynomial ? "_polynomial" : "_no_polynomial") << "_seed" << seed;
    if (on_center > 0) name << "_on_center" << on_center;
    if (offset != 0.0) name << "_offset" << offset;
    if (scale != 1.0) name << "_scale" << scale;
    if (time_scale != 1.0) name << "_time_scale" << time_scale;
    return sanitize_name(name.str());
  }

  void run(Device& device) const override {
    Random random(seed);
    const Points4 center_set = random.points(centers, scale, offset, time_scale);
    Points4 point_set = random.points(points, scale, offset, time_scale);
    const Eigen::Index coinciding = std::min({on_center, points, centers});
    for (Eigen::Index i = 0; i < coinciding; ++i)
      point_set.row(i) = center_set.row(centers - 1 - i);

    const reference::Assembly expected =
        reference::assemble(point_set, center_set, with_polynomial);
    const StridedPoints point_input(point_set);
    const StridedPoints center_input(center_set);
    PaddedBlock output(points, expected.block.cols());
    device.assemble_rbf_block(point_input.view(), center_input.view(), with_polynomial,
                              output.inner());

    EXPECT_TRUE(output.untouched());
    const Eigen::MatrixXd block = output.value();
    EXPECT_TRUE(expect_near(block, expected.block, expected.magnitude, tolerance));
    for (Eigen::Index i = 0; i < coinciding; ++i) {
      EXPECT_EQ(block(i, centers - 1 - i), 0.0) << "phi(0) must be exactly 0 (point " << i << ")";
    }
  }
};

std::shared_ptr<const ConformanceCase> assembly(Eigen::Index points, Eigen::Index centers,
                                                bool with_polynomial, std::uint64_t seed) {
  auto c = std::make_shared<RbfAssemblyCase>();
  c->points = points;
  c->centers = centers;
  c->with_polynomial = with_polynomial;
  c->seed = seed;
  return c;
}

}  // namespace

CaseList rbf_assembly_cases() {
  CaseList cases = {
      assembly(0, 0, true, 1),       assembly(0, 5, true, 2),      assembly(5, 0, true, 3),
      assembly(5, 0, false, 4),      assembly(1, 1, true, 5),      assembly(1, 1, false, 6),
      assembly(5, 7, true, 7),       assembly(7, 5, false, 8),     assembly(11, 13, true, 9),
      assembly(13, 11, false, 10),   assembly(257, 13, true, 11),  assembly(13, 257, false, 12),
      assembly(1031, 257, true, 13), assembly(3001, 37, true, 14),
  };

  auto on_center = std::make_shared<RbfAssemblyCase>();
  on_center->points = 11;
  on_center->centers = 13;
  on_center->seed = 15;
  on_center->on_center = 5;
  cases.push_back(on_center);

  auto far_and_close = std::make_shared<RbfAssemblyCase>();
  far_and_close->points = 257;
  far_and_close->centers = 13;
  far_and_close->seed = 16;
  far_and_close->offset = 1e3;
  far_and_close->scale = 1e-2;
  far_and_close->time_scale = 1e-2;
  cases.push_back(far_and_close);

  auto wide = std::make_shared<RbfAssemblyCase>();
  wide->points = 129;
  wide->centers = 31;
  wide->seed = 17;
  wide->scale = 1e3;
  cases.push_back(wide);
  return cases;
}

}  // namespace posekit::conformance
