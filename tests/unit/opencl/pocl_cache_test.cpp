// The per-process kernel cache: a fresh folder when the variable is unset, removed afterwards; an
// existing setting left alone.
#include "opencl/pocl_cache.hpp"
#include "opencl_test_device.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace posekit::opencl {
namespace {

// A variable of this test's own, so that the process's POCL_CACHE_DIR is not disturbed.
constexpr const char* kVariable = "POSEKIT_TEST_KERNEL_CACHE_DIR";

TEST(PoclCache, UnsetVariableGetsAFreshFolderThatIsRemovedAfterwards) {
  ::unsetenv(kVariable);
  std::filesystem::path folder;
  {
    const ScopedCacheDirectory cache(kVariable);
    ASSERT_FALSE(cache.path().empty());
    folder = cache.path();
    ASSERT_NE(std::getenv(kVariable), nullptr);
    EXPECT_EQ(folder, std::getenv(kVariable));
    EXPECT_TRUE(std::filesystem::is_directory(folder));
    EXPECT_TRUE(std::filesystem::is_empty(folder));
    EXPECT_NE(folder.filename().string().find("-" + std::to_string(::getpid()) + "-"),
              std::string::npos)
        << folder;
    std::filesystem::create_directories(folder / "kcache" / "ab");
    std::ofstream(folder / "kcache" / "ab" / "program.bc") << "compiled kernel";
  }
  EXPECT_FALSE(std::filesystem::exists(folder));
  EXPECT_EQ(std::getenv(kVariable), nullptr);
}

TEST(PoclCache, TwoObjectsGetTwoFolders) {
  ::unsetenv(kVariable);
  const ScopedCacheDirectory first(kVariable);
  ::unsetenv(kVariable);
  const ScopedCacheDirectory second(kVariable);
  EXPECT_FALSE(first.path().empty());
  EXPECT_FALSE(second.path().empty());
  EXPECT_NE(first.path(), second.path());
}

TEST(PoclCache, ExistingSettingIsLeftAlone) {
  ::setenv(kVariable, "/somewhere/the/user/chose", 1);
  {
    const ScopedCacheDirectory cache(kVariable);
    EXPECT_TRUE(cache.path().empty());
    EXPECT_STREQ(std::getenv(kVariable), "/somewhere/the/user/chose");
  }
  EXPECT_STREQ(std::getenv(kVariable), "/somewhere/the/user/chose");
  ::unsetenv(kVariable);
}

TEST(PoclCache, DiscoveryLeavesPoclAFolderOfItsOwn) {
  discover_device();
  const char* folder = std::getenv("POCL_CACHE_DIR");
  ASSERT_NE(folder, nullptr);
  EXPECT_TRUE(std::filesystem::is_directory(folder)) << folder;
}

}  // namespace
}  // namespace posekit::opencl
