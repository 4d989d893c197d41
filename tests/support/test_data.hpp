// Where tests find their data: the project's own files under tests/data and the real poses
// in ../shared/data (or $POSEKIT_DATA_DIR), which may be absent.
#pragma once

#include <Eigen/Core>
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>
#include <optional>
#include <string>

namespace posekit::testing {

/// tests/data in the source tree.
std::filesystem::path project_test_data();

/// The folder of real pose sets, or nullopt when it is not on this machine.
std::optional<std::filesystem::path> shared_data();

/// A file of the real pose sets, e.g. shared_pose("lion-poses/lion-01.obj"); nullopt if absent.
std::optional<std::filesystem::path> shared_pose(const std::string& relative);

/// A fresh empty folder under the system temporary directory, removed by the destructor.
class TemporaryDirectory {
 public:
  TemporaryDirectory();
  ~TemporaryDirectory();
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The entries of `folder` (files and folders), in no particular order.
std::vector<std::filesystem::path> folder_contents(const std::filesystem::path& folder);

/// Passes when |a - b| <= abs_tol + rel_tol * |b| elementwise; on failure names the first bad index.
::testing::AssertionResult matrices_near(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected,
                                         double abs_tol, double rel_tol);

}  // namespace posekit::testing

/// Skips the current test with a message when a real pose file is missing.
#define POSEKIT_REQUIRE_SHARED_POSE(variable, relative)                                     \
  const auto variable##_optional = ::posekit::testing::shared_pose(relative);               \
  if (!variable##_optional) GTEST_SKIP() << "shared pose data not found: " << (relative); \
  const std::filesystem::path& variable = *variable##_optional
