#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>

#include "cgal_reference.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace posekit {
namespace {

using Pairs = std::vector<std::pair<int, int>>;
using Faces = std::vector<int>;

struct Soup {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
};

Soup make_soup(std::initializer_list<std::array<double, 3>> points, std::initializer_list<std::array<int, 3>> triangles) {
  Soup soup;
  soup.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::Index row = 0;
  for (const auto& p : points) soup.vertices.row(row++) << p[0], p[1], p[2];
  soup.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  row = 0;
  for (const auto& t : triangles) soup.faces.row(row++) << t[0], t[1], t[2];
  return soup;
}

Faces faces_of(const Soup& soup) { return self_intersecting_faces(soup.vertices, soup.faces); }

TEST(SelfIntersections, CrossingTrianglesIntersect) {
  const Soup soup = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}},
                              {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(self_intersecting_face_pairs(soup.vertices, soup.faces), (Pairs{{0, 1}}));
  EXPECT_EQ(faces_of(soup), (Faces{0, 1}));
}

TEST(SelfIntersections, SeparateTrianglesDoNot) {
  const Soup soup = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0.1}, {2.5, 0.5, 0.1}, {0.5, 2.5, 0.1}},
                              {{0, 1, 2}, {3, 4, 5}});
  EXPECT_TRUE(faces_of(soup).empty());
}

TEST(SelfIntersections, TouchingAtAPointWithoutSharingAVertexCounts) {
  // The corner of the second triangle lies inside the first, but they share no vertex index.
  const Soup soup = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 1}, {1.5, 0.5, 1}},
                              {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(faces_of(soup), (Faces{0, 1}));
}

TEST(SelfIntersections, EdgeNeighboursCountOnlyWhenFoldedOntoEachOther) {
  // Shared edge 0-1; vertex 3 decides the second face's position.
  const auto with_apex = [](double y, double z) {
    return make_soup({{0, 0, 0}, {1, 0, 0}, {0.3, 1, 0}, {0.6, y, z}}, {{0, 1, 2}, {1, 0, 3}});
  };
  EXPECT_TRUE(faces_of(with_apex(-1.0, 0.0)).empty());   // flat, on opposite sides
  EXPECT_TRUE(faces_of(with_apex(-1.0, 0.7)).empty());   // a fold
  EXPECT_TRUE(faces_of(with_apex(1.0, 1e-9)).empty());   // almost folded flat, not quite
  EXPECT_EQ(faces_of(with_apex(1.0, 0.0)), (Faces{0, 1}));  // folded flat onto each other
  EXPECT_EQ(faces_of(with_apex(0.2, 0.0)), (Faces{0, 1}));  // overlapping, one inside the other
}

TEST(SelfIntersections, VertexNeighboursCountWhenTheyCross) {
  // Both triangles use vertex 0.
  const Soup apart = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0.2}, {0, -1, 0.3}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_TRUE(faces_of(apart).empty());
  // The far edge of the second triangle pierces the first.
  const Soup pierced = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(faces_of(pierced), (Faces{0, 1}));
  // The same with the faces in the other order: the test must look from both faces.
  Soup pierced_swapped = pierced;
  pierced_swapped.faces.row(0).swap(pierced_swapped.faces.row(1));
  EXPECT_EQ(faces_of(pierced_swapped), (Faces{0, 1}));
  // Coplanar, the second triangle lying inside the angle of the first at the shared corner.
  const Soup overlapping = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.2, 0}, {0.2, 0.5, 0}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(faces_of(overlapping), (Faces{0, 1}));
  // Coplanar, side by side, touching only at the shared corner.
  const Soup side_by_side = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_TRUE(faces_of(side_by_side).empty());
}

TEST(SelfIntersections, DuplicateFaceIntersects) {
  const Soup soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 1}});
  EXPECT_EQ(faces_of(soup), (Faces{0, 1}));
}

TEST(SelfIntersections, DegenerateFaceIsReportedAlone) {
  // Face 1 is a needle through face 0 (collinear corners); like CGAL, it is reported as (1, 1)
  // and not tested against face 0. Face 2 repeats a vertex.
  const Soup soup = make_soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 0}, {0.5, 0.5, 1}},
                              {{0, 1, 2}, {3, 4, 5}, {1, 1, 2}});
  EXPECT_EQ(self_intersecting_face_pairs(soup.vertices, soup.faces), (Pairs{{1, 1}, {2, 2}}));
  EXPECT_EQ(faces_of(soup), (Faces{1, 2}));
}

TEST(SelfIntersections, NonManifoldFanReportsOnlyTheFoldedPair) {
  // Three faces on edge 0-1: faces 0 and 2 lie flat on the same side, face 1 stands up.
  const Soup soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0.3, 1, 0}, {0.5, 0, 1}, {0.6, 0.5, 0}},
                              {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  EXPECT_EQ(self_intersecting_face_pairs(soup.vertices, soup.faces), (Pairs{{0, 2}}));
}

TEST(SelfIntersections, ClosedTetrahedronIsClean) {
  const Soup soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  EXPECT_TRUE(faces_of(soup).empty());
  EXPECT_TRUE(self_intersecting_faces(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3i(0, 3)).empty());
}

TEST(SelfIntersections, RejectsBadInput) {
  Soup soup = make_soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}});
  EXPECT_THROW(faces_of(soup), ArgumentError);
  soup.faces(0, 2) = 2;
  soup.vertices(1, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(faces_of(soup), ArgumentError);
}

// A grid of many small faces pushed through itself: enough boxes for the parallel search, and the
// exact answer is known from CGAL's own function.
Soup crumpled_sheet() {
  const int n = 90;
  Soup sheet;
  sheet.vertices.resize(n * n, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = i / double(n - 1);
      const double v = j / double(n - 1);
      // A wavy sheet rolled past a full turn: the waves of the two overlapping layers are out of phase,
      // so the last part passes in and out through the first.
      const double angle = 7.5 * u;
      const double radius = 1.0 - 0.05 * u + 0.04 * std::sin(9.0 * v + 5.0 * u);
      sheet.vertices.row(i * n + j) << radius * std::cos(angle), radius * std::sin(angle),
          2.0 * v + 0.1 * std::cos(11.0 * u);
    }
  }
  sheet.faces.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j;
      sheet.faces.row(f++) << a, a + n, a + 1;
      sheet.faces.row(f++) << a + 1, a + n, a + n + 1;
    }
  }
  return sheet;
}

TEST(SelfIntersections, CrumpledSheetMatchesCgal) {
  const Soup sheet = crumpled_sheet();
  const Faces ours = self_intersecting_faces(sheet.vertices, sheet.faces);
  const auto reference = ::posekit::testing::cgal_self_intersecting_faces(sheet.vertices, sheet.faces);
  ASSERT_TRUE(reference.has_value());
  EXPECT_GT(ours.size(), 100u);
  EXPECT_EQ(ours, *reference);
}

// The broad phase searches a large mesh in parallel tasks: with one thread and with many, and with
// faces whose boxes span most of the others (long slivers through the rolled sheet), the same pairs.
TEST(SelfIntersections, AnyNumberOfThreadsFindsTheSamePairs) {
  Soup sheet = crumpled_sheet();
  const auto first_long = static_cast<int>(sheet.vertices.rows());
  sheet.vertices.conservativeResize(first_long + 9, 3);
  sheet.vertices.bottomRows(9) << -1.5, -1.5, 0.50, 1.5, 1.5, 0.51, 1.5, 1.5, 0.52,  //
      -1.5, 0.1, 1.0, 1.5, 0.1, 1.01, 1.5, 0.2, 1.02,                                //
      0.2, -1.5, 1.5, 0.2, 1.5, 1.51, 0.3, 1.5, 1.5;
  const auto first_face = static_cast<int>(sheet.faces.rows());
  sheet.faces.conservativeResize(first_face + 3, 3);
  for (int k = 0; k < 3; ++k) {
    sheet.faces.row(first_face + k) << first_long + 3 * k, first_long + 3 * k + 1, first_long + 3 * k + 2;
  }

  // Arenas wider than the machine: allowed, so that TBB does not warn that it caps them.
  const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 32);
  const auto pairs_with_threads = [&](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute([&] { return self_intersecting_face_pairs(sheet.vertices, sheet.faces); });
  };
  const Pairs one = pairs_with_threads(1);
  const auto reference = ::posekit::testing::cgal_self_intersecting_faces(sheet.vertices, sheet.faces);
  ASSERT_TRUE(reference.has_value());
  EXPECT_EQ(faces_in_pairs(one), *reference);
  int long_face_pairs = 0;
  for (const auto& [f, g] : one) long_face_pairs += g >= first_face ? 1 : 0;
  EXPECT_GT(long_face_pairs, 10);
  for (int threads : {2, 3, 8, 32}) EXPECT_EQ(pairs_with_threads(threads), one) << threads << " threads";
}

TEST(NewIntersectingFaces, IsTheSetDifference) {
  EXPECT_EQ(new_intersecting_faces({9, 3, 5, 3, 1}, {5, 2, 9}), (Faces{1, 3}));
  EXPECT_EQ(new_intersecting_faces({}, {1, 2}), Faces{});
  EXPECT_EQ(new_intersecting_faces({4, 2}, {}), (Faces{2, 4}));
}

TEST(FacesInPairs, AreTheDistinctFacesOfThePairs) {
  EXPECT_EQ(faces_in_pairs({{3, 7}, {1, 3}, {5, 5}}), (Faces{1, 3, 5, 7}));
  EXPECT_EQ(faces_in_pairs({}), Faces{});
}

}  // namespace
}  // namespace posekit
