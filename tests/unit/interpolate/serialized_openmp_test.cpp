// CHOLMOD's OpenMP regions run on one thread while it works: the runtime it brought in is found,
// the calling thread's max-active-levels is 0 while a guard lives there, other threads keep theirs,
// and the level found before is restored when the guard ends, nested guards included.
#include "interpolate/serialized_openmp.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace posekit::testing {
namespace {

using interpolation::SerializedOpenMpRegions;

TEST(SerializedOpenMpRegions, SerializesTheCallingThreadWhileAGuardLives) {
  const int before = SerializedOpenMpRegions::max_active_levels();
  if (before < 0) GTEST_SKIP() << "no OpenMP runtime in the process (CHOLMOD built without OpenMP)";
  ASSERT_GT(before, 0);
  {
    const SerializedOpenMpRegions outer;
    EXPECT_EQ(SerializedOpenMpRegions::max_active_levels(), 0);
    {
      const SerializedOpenMpRegions inner;
      EXPECT_EQ(SerializedOpenMpRegions::max_active_levels(), 0);
    }
    EXPECT_EQ(SerializedOpenMpRegions::max_active_levels(), 0);
    int other_thread_levels = -2;
    std::thread other([&] { other_thread_levels = SerializedOpenMpRegions::max_active_levels(); });
    other.join();
    EXPECT_GT(other_thread_levels, 0);
  }
  EXPECT_EQ(SerializedOpenMpRegions::max_active_levels(), before);
}

}  // namespace
}  // namespace posekit::testing
