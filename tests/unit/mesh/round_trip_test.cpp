// Every real pose, read from OBJ and written and read back as OBJ, OFF and PLY, is unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "posekit/mesh_io.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

std::vector<std::filesystem::path> shared_obj_files(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> files;
  for (const auto& folder : std::filesystem::directory_iterator(root)) {
    if (!folder.is_directory()) continue;
    for (const auto& entry : std::filesystem::directory_iterator(folder.path())) {
      if (entry.is_regular_file() && entry.path().extension() == ".obj") files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(RoundTrip, EverySharedPoseInEveryFormatIsExact) {
  const auto root = testing::shared_data();
  if (!root) GTEST_SKIP() << "shared pose data not found (set POSEKIT_DATA_DIR)";
  const std::vector<std::filesystem::path> files = shared_obj_files(*root);
  ASSERT_FALSE(files.empty()) << "no .obj file under " << *root;
  testing::TemporaryDirectory folder;
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    const Mesh original = read_mesh(file);
    ASSERT_GT(original.faces.rows(), 0);
    for (const char* extension : {".obj", ".off", ".ply"}) {
      const std::filesystem::path copy = folder.path() / (file.stem().string() + extension);
      write_mesh(copy, original);
      const Mesh back = read_mesh(copy);
      // Exact comparison: 17 significant digits (or binary PLY) must give back the same doubles.
      EXPECT_TRUE(back.vertices == original.vertices) << extension;
      EXPECT_TRUE(back.faces == original.faces) << extension;
      std::filesystem::remove(copy);
    }
  }
}

}  // namespace
}  // namespace posekit
