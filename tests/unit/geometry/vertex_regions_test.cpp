#include <posekit/topology.hpp>
#include <posekit/vertex_regions.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace posekit {
namespace {

// A strip of `length` squares, two triangles each, along a row of 2 (length + 1) vertices: vertex
// 2 i is on the bottom edge, 2 i + 1 on the top one. `offset` numbers the strip's vertices from there.
Eigen::MatrixX3i strip_faces(int length, int offset = 0) {
  Eigen::MatrixX3i faces(2 * length, 3);
  for (int i = 0; i < length; ++i) {
    const int a = offset + 2 * i;
    faces.row(2 * i) << a, a + 2, a + 1;
    faces.row(2 * i + 1) << a + 1, a + 2, a + 3;
  }
  return faces;
}

std::vector<char> flags_of_columns(int vertex_count, int first, int last) {
  std::vector<char> flags(static_cast<size_t>(vertex_count), 0);
  for (int column = first; column <= last; ++column) {
    flags[static_cast<size_t>(2 * column)] = 1;
    flags[static_cast<size_t>(2 * column + 1)] = 1;
  }
  return flags;
}

// A band across the strip cuts it in two: the shorter end joins the band, the longer stays out,
// whichever end the vertex numbers begin at.
TEST(WithCutOffParts, TheShorterEndJoinsABandAcrossTheStrip) {
  const int columns = 21;
  const AdjacencyLists neighbours = vertex_neighbours(strip_faces(columns - 1), 2 * columns);
  EXPECT_EQ(with_cut_off_parts(flags_of_columns(2 * columns, 14, 15), neighbours),
            flags_of_columns(2 * columns, 14, columns - 1));
  EXPECT_EQ(with_cut_off_parts(flags_of_columns(2 * columns, 5, 6), neighbours), flags_of_columns(2 * columns, 0, 6));
}

// Of two equal ends, the one with the lower vertex numbers stays out.
TEST(WithCutOffParts, OfTwoEqualEndsTheFirstStaysOut) {
  const int columns = 11;
  const AdjacencyLists neighbours = vertex_neighbours(strip_faces(columns - 1), 2 * columns);
  EXPECT_EQ(with_cut_off_parts(flags_of_columns(2 * columns, 5, 5), neighbours), flags_of_columns(2 * columns, 5, 10));
}

// A region that cuts nothing off, or touches the strip's end, is returned as it is.
TEST(WithCutOffParts, ARegionThatCutsNothingOffStaysAsItIs) {
  const int columns = 11;
  const AdjacencyLists neighbours = vertex_neighbours(strip_faces(columns - 1), 2 * columns);
  std::vector<char> corner(2 * columns, 0);
  corner[10] = 1;  // one vertex of the bottom edge: the strip stays connected around it
  EXPECT_EQ(with_cut_off_parts(corner, neighbours), corner);
  const std::vector<char> end = flags_of_columns(2 * columns, 8, columns - 1);
  EXPECT_EQ(with_cut_off_parts(end, neighbours), end);
  const std::vector<char> none(2 * columns, 0);
  EXPECT_EQ(with_cut_off_parts(none, neighbours), none);
  const std::vector<char> all(2 * columns, 1);
  EXPECT_EQ(with_cut_off_parts(all, neighbours), all);
}

// Each piece of a mesh keeps its own largest part: a second strip the band does not touch stays out,
// however small it is, and so does a vertex no face uses.
TEST(WithCutOffParts, ASeparatePieceIsNotCutOff) {
  const int columns = 21;
  const int small_columns = 3;
  Eigen::MatrixX3i faces(2 * (columns - 1) + 2 * (small_columns - 1), 3);
  faces << strip_faces(columns - 1), strip_faces(small_columns - 1, 2 * columns);
  const int vertex_count = 2 * (columns + small_columns) + 1;
  const AdjacencyLists neighbours = vertex_neighbours(faces, vertex_count);
  const std::vector<char> band = flags_of_columns(vertex_count, 3, 3);
  const std::vector<char> region = with_cut_off_parts(band, neighbours);
  EXPECT_EQ(region, flags_of_columns(vertex_count, 0, 3));
}

}  // namespace
}  // namespace posekit
