#include "test_data.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

namespace posekit::testing {

std::filesystem::path project_test_data() { return POSEKIT_TEST_DATA_DIR; }

std::optional<std::filesystem::path> shared_data() {
  const char* override_dir = std::getenv("POSEKIT_DATA_DIR");
  std::filesystem::path folder = override_dir != nullptr ? override_dir : POSEKIT_SHARED_DATA_DIR;
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return std::nullopt;
  return folder;
}

std::optional<std::filesystem::path> shared_pose(const std::string& relative) {
  const auto folder = shared_data();
  if (!folder) return std::nullopt;
  std::filesystem::path file = *folder / relative;
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return std::nullopt;
  return file;
}

TemporaryDirectory::TemporaryDirectory() {
  static std::atomic<int> counter{0};
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::ostringstream name;
    name << "posekit-test-" << random() << "-" << counter++;
    path_ = std::filesystem::temp_directory_path() / name.str();
    if (std::filesystem::create_directory(path_)) return;
  }
  throw std::runtime_error("cannot create a temporary directory");
}

TemporaryDirectory::~TemporaryDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

::testing::AssertionResult matrices_near(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected,
                                         double abs_tol, double rel_tol) {
  if (actual.rows() != expected.rows() || actual.cols() != expected.cols()) {
    return ::testing::AssertionFailure() << "size " << actual.rows() << "x" << actual.cols()
                                         << " differs from expected " << expected.rows() << "x"
                                         << expected.cols();
  }
  for (Eigen::Index j = 0; j < actual.cols(); ++j) {
    for (Eigen::Index i = 0; i < actual.rows(); ++i) {
      const double a = actual(i, j);
      const double b = expected(i, j);
      const bool finite_mismatch = std::isfinite(a) != std::isfinite(b);
      if (finite_mismatch || std::isnan(a) || std::isnan(b) ||
          std::abs(a - b) > abs_tol + rel_tol * std::abs(b)) {
        return ::testing::AssertionFailure()
               << "first mismatch at (" << i << ", " << j << "): " << a << " vs expected " << b
               << " (difference " << std::abs(a - b) << ", allowed " << abs_tol + rel_tol * std::abs(b)
               << ")";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

std::vector<std::filesystem::path> folder_contents(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> entries;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) entries.push_back(entry.path());
  return entries;
}

}  // namespace posekit::testing
