#include <gtest/gtest.h>

#include <posekit/blend_files.hpp>
#include <posekit/error.hpp>

#include "test_data.hpp"

#include <fstream>

namespace posekit {
namespace {

std::filesystem::path write_file(const testing::TemporaryDirectory& folder, const std::string& name,
                                 const std::string& text) {
  const std::filesystem::path path = folder.path() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The InputError of reading `text` as constraints of a 10-vertex mesh.
std::string constraint_error(const std::string& text) {
  const testing::TemporaryDirectory folder;
  const std::filesystem::path file = write_file(folder, "c.txt", text);
  try {
    read_point_constraints(file, 10);
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), file.string());
    return error.what();
  }
  ADD_FAILURE() << "no error for: " << text;
  return {};
}

TEST(PointConstraints, ReadCommentsBlankLinesTabsAndGroups) {
  const testing::TemporaryDirectory folder;
  const std::filesystem::path file =
      write_file(folder, "c.txt", "# vertex x y z\n\n3 1 2 3\r\n 7\t-1.5e-1   0 4 # a foot\n   # nothing\n9 0 0 1e2 legs\n");
  const PointConstraints c = read_point_constraints(file, 10);
  ASSERT_EQ(c.vertices, (std::vector<int>{3, 7, 9}));
  EXPECT_EQ(c.positions.row(1), Eigen::RowVector3d(-0.15, 0.0, 4.0));
  EXPECT_EQ(c.positions(2, 2), 100.0);
  EXPECT_EQ(c.groups, (std::vector<std::string>{"", "", "legs"}));
  EXPECT_EQ(c.lines, (std::vector<long>{3, 4, 6}));
}

TEST(PointConstraints, NameTheLineOfEachProblem) {
  EXPECT_NE(constraint_error("1 0 0 0\n2 0 0\n").find(":2: expected 'VERTEX X Y Z [GROUP]', found 3 fields"),
            std::string::npos);
  EXPECT_NE(constraint_error("\n10 0 0 0\n").find(":2: vertex index 10 is outside [0, 10)"), std::string::npos);
  EXPECT_NE(constraint_error("-1 0 0 0\n").find(":1: vertex index -1 is outside"), std::string::npos);
  EXPECT_NE(constraint_error("1.5 0 0 0\n").find(":1: '1.5' is not a vertex index"), std::string::npos);
  EXPECT_NE(constraint_error("1 0 nan 0\n").find(":1: y 'nan' is not finite"), std::string::npos);
  EXPECT_NE(constraint_error("1 0 0 inf\n").find(":1: z 'inf' is not finite"), std::string::npos);
  EXPECT_NE(constraint_error("1 0 0 1e999\n").find(":1: z '1e999' is not finite"), std::string::npos);
  EXPECT_NE(constraint_error("1 0 0 0x\n").find(":1: '0x' is not a number (z)"), std::string::npos);
  EXPECT_NE(constraint_error("1 0 0 0\n#\n1 2 2 2\n").find(":3: vertex 1 is already constrained on line 1"),
            std::string::npos);
  EXPECT_NE(constraint_error("# only a comment\n\n").find("lists no constraint"), std::string::npos);
  EXPECT_THROW(read_point_constraints("/nonexistent/constraints.txt", 10), InputError);
}

TEST(SkinningWeights, ReadOneRowPerVertex) {
  const testing::TemporaryDirectory folder;
  const Eigen::MatrixXd w =
      read_skinning_weights(write_file(folder, "w.txt", "# bones: arm, forearm\n1 0\n0.5\t0.5\n\n0 1 # tip\n"), 3);
  Eigen::MatrixXd expected(3, 2);
  expected << 1, 0, 0.5, 0.5, 0, 1;
  EXPECT_EQ(w, expected);
}

TEST(SkinningWeights, RejectRaggedRowsWrongCountsAndZeroRows) {
  const testing::TemporaryDirectory folder;
  const auto message = [&](const std::string& text, int vertices) -> std::string {
    try {
      read_skinning_weights(write_file(folder, "w.txt", text), vertices);
    } catch (const InputError& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(message("1 0\n1\n", 2).find(":2: row has 1 weights; the first row has 2"), std::string::npos);
  EXPECT_NE(message("1 0\n", 2).find("has 1 weight rows for 2 vertices"), std::string::npos);
  EXPECT_NE(message("1 0\n0 1\n1 1\n", 2).find(":3: more rows than the 2 vertices"), std::string::npos);
  EXPECT_NE(message("1 0\n0 0\n", 2).find(":2: every weight of vertex 1 is zero"), std::string::npos);
  EXPECT_NE(message("1 nan\n0 1\n", 2).find(":1: weight 'nan' is not finite"), std::string::npos);
}

}  // namespace
}  // namespace posekit
