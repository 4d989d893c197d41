// Reading the small valid meshes of tests/data/valid in every format, and errors that need a file system.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

std::filesystem::path valid(const std::string& name) { return testing::project_test_data() / "valid" / name; }

std::filesystem::path malformed(const std::string& name) { return testing::project_test_data() / "malformed" / name; }

Mesh tetrahedron() {
  Mesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1.5;
  mesh.faces.resize(4, 3);
  mesh.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return mesh;
}

class ValidTetrahedron : public ::testing::TestWithParam<std::string> {};

TEST_P(ValidTetrahedron, ReadsTheSameVerticesAndFacesInFileOrder) {
  std::vector<std::string> warnings;
  const Mesh mesh = read_mesh(valid(GetParam()), &warnings);
  const Mesh expected = tetrahedron();
  EXPECT_EQ(mesh.vertices, expected.vertices);
  EXPECT_EQ(mesh.faces, expected.faces);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

INSTANTIATE_TEST_SUITE_P(Formats, ValidTetrahedron,
                         ::testing::Values("tetrahedron.obj", "tetrahedron_crlf_tabs.obj", "tetrahedron_bom.obj",
                                           "tetrahedron.off", "tetrahedron_colors.off", "tetrahedron_normals.off",
                                           "tetrahedron_ascii.ply", "tetrahedron_binary.ply",
                                           "tetrahedron_binary_big_endian.ply", "tetrahedron_extra_properties.ply"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.substr(0, info.param.find('.'));
                           return name + "_" + info.param.substr(info.param.find('.') + 1);
                         });

TEST(ReadMesh, ExtensionIsCaseInsensitive) {
  testing::TemporaryDirectory folder;
  const std::filesystem::path upper = folder.path() / "TETRAHEDRON.OBJ";
  std::filesystem::copy_file(valid("tetrahedron.obj"), upper);
  EXPECT_EQ(read_mesh(upper).faces, tetrahedron().faces);
  const std::filesystem::path mixed = folder.path() / "tetrahedron.Ply";
  std::filesystem::copy_file(valid("tetrahedron_binary.ply"), mixed);
  EXPECT_EQ(read_mesh(mixed).vertices, tetrahedron().vertices);
}

TEST(ReadMesh, FormatFromExtension) {
  EXPECT_EQ(mesh_format_from_extension("a/b.obj"), MeshFormat::obj);
  EXPECT_EQ(mesh_format_from_extension("b.OFF"), MeshFormat::off);
  EXPECT_EQ(mesh_format_from_extension("b.pLy"), MeshFormat::ply);
  EXPECT_THROW(mesh_format_from_extension("mesh.stl"), InputError);
  EXPECT_THROW(mesh_format_from_extension("mesh"), InputError);
  EXPECT_THROW(mesh_format_from_extension("obj"), InputError);
}

TEST(ReadMesh, MissingFileAndDirectoryAreInputErrors) {
  testing::TemporaryDirectory folder;
  const std::filesystem::path missing = folder.path() / "missing.obj";
  try {
    read_mesh(missing);
    FAIL() << "a missing file was read";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), missing.string());
    EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos) << error.what();
  }
  const std::filesystem::path directory = folder.path() / "folder.obj";
  std::filesystem::create_directory(directory);
  try {
    read_mesh(directory);
    FAIL() << "a directory was read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("is a directory"), std::string::npos) << error.what();
  }
}

// The message names the line of the problem where the format has lines.
TEST(ReadMesh, ErrorsNameTheLine) {
  const std::vector<std::pair<std::string, long>> expected_lines = {
      {"quad_face.obj", 5},
      {"nan_coordinate.obj", 2},
      {"truncated_mid_line.obj", 9},
      {"truncated_counts.off", 2},
      {"non_numeric_coordinate.off", 4},
      {"face_index_out_of_range.ply", 17},
      {"face_index_2147483648.ply", 14},
      {"face_index_out_of_range.obj", 8},
      {"bad_header.off", 1},
  };
  for (const auto& [name, line] : expected_lines) {
    try {
      read_mesh(malformed(name));
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.line(), line) << error.what();
      EXPECT_NE(std::string(error.what()).find(name + ":" + std::to_string(line) + ": "), std::string::npos)
          << error.what();
    }
  }
}

TEST(ReadMesh, DefectsAreWarningsNotErrors) {
  const std::filesystem::path file = valid("with_defects.obj");
  std::vector<std::string> warnings;
  const Mesh mesh = read_mesh(file, &warnings);
  EXPECT_EQ(mesh.vertices.rows(), 6);
  EXPECT_EQ(mesh.faces.rows(), 6);
  ASSERT_EQ(warnings.size(), 2U);
  for (const std::string& warning : warnings) {
    EXPECT_EQ(warning.find('\n'), std::string::npos);
    EXPECT_EQ(warning.rfind(file.string() + ": ", 0), 0U) << warning;
  }
  EXPECT_NE(warnings[0].find("1 unreferenced vertex (used by no face; first: vertex 4)"), std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("2 degenerate faces (repeated vertex or zero area; first: face 4)"), std::string::npos)
      << warnings[1];
  EXPECT_NO_THROW(read_mesh(file));
}

}  // namespace
}  // namespace posekit
