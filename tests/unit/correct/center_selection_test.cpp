// Where the greedy fit puts its centers: the approximate farthest pair, farthest-point sampling of
// the first batch, and the per-round choice among the worst constraints.
#include "correct/center_selection.hpp"

#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

namespace posekit {
namespace {

using Eigen::Index;

Points4 random_points(std::mt19937_64& engine, Index count) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Points4 points(count, 4);
  for (Index i = 0; i < points.size(); ++i) points.data()[i] = coordinate(engine);
  return points;
}

double distance(const Points4& points, Index a, Index b) {
  return (points.row(a) - points.row(b)).norm();
}

double exact_diameter(const Points4& points) {
  double largest = 0;
  for (Index a = 0; a < points.rows(); ++a) {
    for (Index b = a + 1; b < points.rows(); ++b) largest = std::max(largest, distance(points, a, b));
  }
  return largest;
}

TEST(FarthestPair, FindsTheEndsOfAThinCloud) {
  std::mt19937_64 engine(1);
  std::uniform_real_distribution<double> along(0.0, 1.0);
  std::uniform_real_distribution<double> across(-0.01, 0.01);
  Points4 points(400, 4);
  for (Index i = 0; i < points.rows(); ++i) {
    const double s = along(engine);
    points.row(i) << s, 2.0 * s + across(engine), across(engine), 0.5 * s;
  }
  points.row(123) << -1.0, -2.0, 0.0, -0.5;  // the two ends
  points.row(321) << 2.0, 4.0, 0.0, 1.0;
  const auto [a, b] = detail::approximately_farthest_pair(points);
  EXPECT_EQ(std::set<Index>({a, b}), std::set<Index>({123, 321}));
}

TEST(FarthestPair, IsCloseToTheExactDiameterOfARandomCloud) {
  for (const unsigned seed : {2u, 3u, 4u}) {
    std::mt19937_64 engine(seed);
    const Points4 points = random_points(engine, 600);
    const auto [a, b] = detail::approximately_farthest_pair(points);
    EXPECT_GE(distance(points, a, b), 0.9 * exact_diameter(points)) << "seed " << seed;
  }
}

TEST(SpreadCenters, StartsWithTheFarPairAndPacksAsWellAsItCovers) {
  std::mt19937_64 engine(5);
  const Points4 points = random_points(engine, 3000);
  const std::vector<Index> chosen = detail::spread_centers(points, 64, 1e-9);
  ASSERT_EQ(chosen.size(), 64u);
  const auto [a, b] = detail::approximately_farthest_pair(points);
  EXPECT_EQ(chosen[0], a);
  EXPECT_EQ(chosen[1], b);
  EXPECT_EQ(std::set<Index>(chosen.begin(), chosen.end()).size(), chosen.size());

  // Farthest-point sampling: no two chosen points are closer than the farthest any point lies
  // from the chosen set.
  double packing = 1e300;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    for (std::size_t j = i + 1; j < chosen.size(); ++j) {
      packing = std::min(packing, distance(points, chosen[i], chosen[j]));
    }
  }
  double covering = 0;
  for (Index p = 0; p < points.rows(); ++p) {
    double nearest = 1e300;
    for (const Index c : chosen) nearest = std::min(nearest, distance(points, p, c));
    covering = std::max(covering, nearest);
  }
  EXPECT_GE(packing, covering);
  EXPECT_GT(covering, 0.0);
}

TEST(SpreadCenters, StopsWhenOnlyRepeatedPointsRemain) {
  std::mt19937_64 engine(6);
  const Points4 distinct = random_points(engine, 10);
  Points4 points(50, 4);
  for (Index i = 0; i < 50; ++i) points.row(i) = distinct.row(i % 10);
  const std::vector<Index> chosen = detail::spread_centers(points, 30, 1e-9);
  ASSERT_EQ(chosen.size(), 10u);
  std::set<Index> classes;
  for (const Index c : chosen) classes.insert(c % 10);
  EXPECT_EQ(classes.size(), 10u);
}

class SelectNewCenters : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937_64 engine(7);
    positions = random_points(engine, 500);
    std::uniform_real_distribution<double> error(0.0, 1.0);
    errors.resize(positions.rows());
    for (Index i = 0; i < errors.size(); ++i) errors(i) = error(engine);
    is_center.assign(static_cast<std::size_t>(positions.rows()), false);
    for (Index i = 0; i < positions.rows(); i += 10) is_center[static_cast<std::size_t>(i)] = true;
    centers = centers_of(is_center);
  }

  Points4 centers_of(const std::vector<bool>& flags) const {
    std::vector<Index> indices;
    for (Index i = 0; i < positions.rows(); ++i) {
      if (flags[static_cast<std::size_t>(i)]) indices.push_back(i);
    }
    Points4 result(static_cast<Index>(indices.size()), 4);
    for (std::size_t k = 0; k < indices.size(); ++k) result.row(static_cast<Index>(k)) = positions.row(indices[k]);
    return result;
  }

  Points4 positions;
  Eigen::VectorXd errors;
  std::vector<bool> is_center;
  Points4 centers;
};

TEST_F(SelectNewCenters, ChoosesAmongTheWorstNonCentersStartingWithTheWorst) {
  detail::CenterCandidates selection;
  selection.candidates = 60;
  selection.count = 12;
  selection.max_squared_error = 0.3;
  selection.min_separation = 1e-9;
  const std::vector<Index> chosen =
      detail::select_new_centers(positions, errors, is_center, centers, selection);
  ASSERT_EQ(chosen.size(), 12u);
  EXPECT_EQ(std::set<Index>(chosen.begin(), chosen.end()).size(), chosen.size());

  std::vector<Index> ranked;
  for (Index i = 0; i < positions.rows(); ++i) {
    if (!is_center[static_cast<std::size_t>(i)]) ranked.push_back(i);
  }
  std::sort(ranked.begin(), ranked.end(), [&](Index a, Index b) { return errors(a) > errors(b); });
  ranked.resize(60);
  EXPECT_EQ(chosen.front(), ranked.front());
  for (const Index c : chosen) {
    EXPECT_FALSE(is_center[static_cast<std::size_t>(c)]) << c;
    EXPECT_NE(std::find(ranked.begin(), ranked.end(), c), ranked.end()) << c << " is not among the 60 worst";
  }
}

TEST_F(SelectNewCenters, IgnoresConstraintsThatAlreadyFit) {
  detail::CenterCandidates selection;
  selection.candidates = 100;
  selection.count = 50;
  selection.max_squared_error = 0.99;
  const std::vector<Index> chosen =
      detail::select_new_centers(positions, errors, is_center, centers, selection);
  for (const Index c : chosen) EXPECT_GE(errors(c), 0.99);
  Index violating = 0;
  for (Index i = 0; i < positions.rows(); ++i) {
    violating += !is_center[static_cast<std::size_t>(i)] && errors(i) >= 0.99;
  }
  EXPECT_EQ(static_cast<Index>(chosen.size()), violating);

  selection.max_squared_error = 2.0;
  EXPECT_TRUE(detail::select_new_centers(positions, errors, is_center, centers, selection).empty());
}

// After the worst candidate, candidates far from every center win over slightly worse ones
// huddled around an existing center.
TEST(SelectNewCentersGeometry, PrefersCandidatesFarFromExistingCenters) {
  Points4 positions(11, 4);
  positions.row(0) << 0, 0, 0, 0;  // the existing center
  for (Index k = 0; k < 5; ++k) positions.row(1 + k) << 0.01 * (k + 1), 0, 0, 0;         // near it
  for (Index k = 0; k < 5; ++k) positions.row(6 + k) << 0, 1.0, 0.3 * k, 0.1 * k;       // far away
  Eigen::VectorXd errors(11);
  errors << 0, 10, 9.9, 9.8, 9.7, 9.6, 5, 4.9, 4.8, 4.7, 4.6;
  std::vector<bool> is_center(11, false);
  is_center[0] = true;
  const Points4 centers = positions.topRows(1);
  detail::CenterCandidates selection;
  selection.candidates = 10;
  selection.count = 4;
  selection.max_squared_error = 1.0;
  const std::vector<Index> chosen =
      detail::select_new_centers(positions, errors, is_center, centers, selection);
  ASSERT_EQ(chosen.size(), 4u);
  EXPECT_EQ(chosen[0], 1);
  for (std::size_t k = 1; k < chosen.size(); ++k) {
    EXPECT_GE(chosen[k], 6) << "pick " << k << " is next to the existing center";
  }
}

TEST(SelectNewCentersGeometry, SkipsCandidatesOnTopOfACenterOrOfEachOther) {
  Points4 positions(5, 4);
  positions.row(0) << 0, 0, 0, 0;
  positions.row(1) << 0, 0, 0, 0;        // same place as center 0, worst error
  positions.row(2) << 1, 0, 0, 0;
  positions.row(3) << 1, 0, 0, 1e-12;    // all but on top of 2
  positions.row(4) << 0, 1, 0, 0;
  Eigen::VectorXd errors(5);
  errors << 0, 9, 8, 7, 1;
  std::vector<bool> is_center = {true, false, false, false, false};
  detail::CenterCandidates selection;
  selection.candidates = 4;
  selection.count = 4;
  selection.max_squared_error = 0.5;
  selection.min_separation = 1e-9;
  const std::vector<Index> chosen =
      detail::select_new_centers(positions, errors, is_center, positions.topRows(1), selection);
  EXPECT_EQ(chosen, (std::vector<Index>{2, 4}));
}

TEST(SelectNewCentersGeometry, RejectsMismatchedSizes) {
  const Points4 positions = Points4::Zero(4, 4);
  detail::CenterCandidates selection;
  EXPECT_THROW(detail::select_new_centers(positions, Eigen::VectorXd::Zero(3),
                                          std::vector<bool>(4, false), Points4(0, 4), selection),
               ArgumentError);
  EXPECT_THROW(detail::select_new_centers(positions, Eigen::VectorXd::Zero(4),
                                          std::vector<bool>(5, false), Points4(0, 4), selection),
               ArgumentError);
}

}  // namespace
}  // namespace posekit
