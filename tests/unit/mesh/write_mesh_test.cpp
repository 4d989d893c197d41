// write_mesh: exact doubles in every format, and the whole-or-nothing rule for the output file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <string>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

std::set<std::string> folder_entries(const std::filesystem::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

// A strip of triangles whose coordinates are hard to print: tiny, huge, subnormal, negative zero,
// values with no short decimal form, and random doubles of every magnitude (fixed seed).
Mesh awkward_mesh() {
  const int vertex_count = 60;
  Mesh mesh;
  mesh.vertices.resize(vertex_count, 3);
  std::mt19937_64 random(12345);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int v = 0; v < vertex_count; ++v) {
    for (int k = 0; k < 3; ++k) mesh.vertices(v, k) = std::ldexp(mantissa(random), exponent(random));
  }
  mesh.vertices.row(0) << 0.1, 1.0 / 3.0, -0.0;
  mesh.vertices.row(1) << std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
      std::numeric_limits<double>::lowest();
  mesh.vertices.row(2) << std::numeric_limits<double>::min(), 2.0 / 3.0, std::nextafter(1.0, 2.0);
  mesh.faces.resize(vertex_count - 2, 3);
  for (int f = 0; f < vertex_count - 2; ++f) mesh.faces.row(f) << f, f + 1, f + 2;
  return mesh;
}

bool same_bits(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(WriteMesh, EveryFormatReadsBackBitForBit) {
  testing::TemporaryDirectory folder;
  const Mesh mesh = awkward_mesh();
  for (const char* name : {"awkward.obj", "awkward.off", "awkward.ply", "AWKWARD.OBJ"}) {
    const std::filesystem::path file = folder.path() / name;
    write_mesh(file, mesh);
    const Mesh back = read_mesh(file);
    EXPECT_TRUE(same_bits(back.vertices, mesh.vertices)) << name;
    EXPECT_EQ(back.faces, mesh.faces) << name;
  }
  EXPECT_EQ(folder_entries(folder.path()),
            (std::set<std::string>{"awkward.obj", "awkward.off", "awkward.ply", "AWKWARD.OBJ"}));
}

TEST(WriteMesh, MissingFolderThrowsAndLeavesNothing) {
  testing::TemporaryDirectory folder;
  const std::filesystem::path target = folder.path() / "missing" / "out.obj";
  try {
    write_mesh(target, awkward_mesh());
    FAIL() << "writing into a missing folder succeeded";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), target.string());
    EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(target.parent_path()));
  EXPECT_TRUE(folder_entries(folder.path()).empty());
}

TEST(WriteMesh, ReplacesAnExistingFileWhole) {
  testing::TemporaryDirectory folder;
  const std::filesystem::path target = folder.path() / "out.off";
  {
    std::ofstream old(target);
    for (int i = 0; i < 100000; ++i) old << "old content that is longer than the new mesh\n";
  }
  const auto old_size = std::filesystem::file_size(target);
  const Mesh mesh = awkward_mesh();
  write_mesh(target, mesh);
  EXPECT_LT(std::filesystem::file_size(target), old_size);
  const Mesh back = read_mesh(target);
  EXPECT_TRUE(same_bits(back.vertices, mesh.vertices));
  EXPECT_EQ(back.faces, mesh.faces);
  EXPECT_EQ(folder_entries(folder.path()), std::set<std::string>{"out.off"});
}

TEST(WriteMesh, FailedRenameRemovesTheTemporaryFile) {
  testing::TemporaryDirectory folder;
  // A non-empty folder where the file should go: the data are written, but the rename fails.
  const std::filesystem::path target = folder.path() / "taken.ply";
  std::filesystem::create_directory(target);
  std::ofstream(target / "keep.txt") << "kept";
  EXPECT_THROW(write_mesh(target, awkward_mesh()), InputError);
  EXPECT_EQ(folder_entries(folder.path()), std::set<std::string>{"taken.ply"});
  EXPECT_EQ(folder_entries(target), std::set<std::string>{"keep.txt"});
}

TEST(WriteMesh, BadNamesAndBadMeshesWriteNothing) {
  testing::TemporaryDirectory folder;
  EXPECT_THROW(write_mesh(folder.path() / "out.stl", awkward_mesh()), InputError);
  Mesh out_of_range = awkward_mesh();
  out_of_range.faces(3, 2) = 60;
  EXPECT_THROW(write_mesh(folder.path() / "out.obj", out_of_range), ArgumentError);
  Mesh not_finite = awkward_mesh();
  not_finite.vertices(5, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(write_mesh(folder.path() / "out.obj", not_finite), ArgumentError);
  EXPECT_TRUE(folder_entries(folder.path()).empty());
}

}  // namespace
}  // namespace posekit
