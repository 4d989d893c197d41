// Valid files with bytes cut, changed, inserted or removed (fixed seed): read_mesh must accept them
// as a valid mesh or refuse them with a one-line InputError, never fail in any other way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

constexpr int kMutationsPerFile = 150;

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::stringstream bytes;
  bytes << stream.rdbuf();
  return bytes.str();
}

// mt19937's output is fixed by the standard, so every platform mutates the same way.
std::string mutate(std::string bytes, std::mt19937& random) {
  static const std::string kTextBytes = "0123456789-+.eE \n\t#/";
  const unsigned kind = random() % 5;
  const unsigned edits = 1 + random() % 3;
  for (unsigned e = 0; e < edits && !bytes.empty(); ++e) {
    const std::size_t at = random() % bytes.size();
    switch (kind) {
      case 0:
        bytes.resize(at);
        break;
      case 1:
        bytes[at] = static_cast<char>(random() & 0xff);
        break;
      case 2:
        bytes[at] = kTextBytes[random() % kTextBytes.size()];
        break;
      case 3:
        bytes.insert(at, std::to_string(static_cast<std::uint64_t>(random()) * (random() % 2 == 0 ? 1 : 1000000000)));
        break;
      default:
        bytes.erase(at, random() % 8);
        break;
    }
  }
  return bytes;
}

TEST(MutatedMesh, IsReadOrRefusedCleanly) {
  testing::TemporaryDirectory folder;
  std::mt19937 random(20240611);
  int accepted = 0;
  int refused = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(testing::project_test_data() / "valid")) {
    const std::string extension = entry.path().extension().string();
    if (extension == ".obj" || extension == ".off" || extension == ".ply") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  for (const std::filesystem::path& file : files) {
    const std::string original = read_bytes(file);
    const std::filesystem::path mutated = folder.path() / ("mutated" + file.extension().string());
    for (int m = 0; m < kMutationsPerFile; ++m) {
      const std::string bytes = mutate(original, random);
      std::ofstream(mutated, std::ios::binary | std::ios::trunc) << bytes;
      try {
        const Mesh mesh = read_mesh(mutated);
        ++accepted;
        ASSERT_GT(mesh.faces.rows(), 0);
        ASSERT_TRUE(mesh.vertices.allFinite());
        ASSERT_GE(mesh.faces.minCoeff(), 0);
        ASSERT_LT(mesh.faces.maxCoeff(), mesh.vertices.rows());
      } catch (const InputError& error) {
        ++refused;
        ASSERT_EQ(std::string(error.what()).find('\n'), std::string::npos) << error.what();
      } catch (const std::exception& error) {
        FAIL() << file.filename() << " mutation " << m << " threw something else: " << error.what();
      }
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace posekit
