// The GLSL mirror of kernel_math.h (shaders/kernel_math.glsl) against the C definitions, through
// the probe shader: the generated constants bit for bit, the double-precision logarithm that GLSL
// lacks (within 1 ulp of the exact value over 1e-300 ... 1e300), and the step-factor power.
#include "vulkan_test_support.hpp"

#include "common/kernel_math.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <random>
#include <vector>

namespace posekit::vulkan {
namespace {

std::uint64_t bits_of(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

// |actual - exact| in units of the last place of the double nearest to `exact`.
double ulps(double actual, long double exact) {
  const double rounded = static_cast<double>(exact);
  const double ulp = std::nextafter(std::abs(rounded), INFINITY) - std::abs(rounded);
  return static_cast<double>(std::abs(static_cast<long double>(actual) - exact) / ulp);
}

TEST(KernelMathGlsl, ConstantsMatchTheCHeaderBitForBit) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  std::vector<double> expected;
#define POSEKIT_COLLECT(name) expected.push_back((double)(name));
  PK_KERNEL_DOUBLE_CONSTANTS(POSEKIT_COLLECT)
#undef POSEKIT_COLLECT
  const std::vector<double> actual = testing::run_probe(*device, testing::Probe::constants,
                                                        std::vector<double>(expected.size(), 0.0));
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(bits_of(actual[i]), bits_of(expected[i]))
        << "constant " << i << " of PK_KERNEL_DOUBLE_CONSTANTS: " << actual[i] << " vs "
        << expected[i];
  }
}

TEST(KernelMathGlsl, LogIsWithinOneUlpFrom1eMinus300To1e300) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  std::mt19937_64 engine(2024);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  std::uniform_real_distribution<double> near_one(0.7, 1.4);
  std::vector<double> x;
  for (int i = 0; i < 1000000; ++i) x.push_back(std::pow(10.0, exponent(engine)));
  for (int i = 0; i < 200000; ++i) x.push_back(near_one(engine));
  // Powers of two (k ln 2 exactly), the ends of the range and the sqrt(2)/2 switch of the
  // reduction.
  for (int k = -1022; k <= 1023; ++k) x.push_back(std::ldexp(1.0, k));
  for (double special :
       {DBL_MIN, DBL_MAX, 1e-300, 1e300, 1.0, std::sqrt(0.5), std::sqrt(2.0),
        std::nextafter(std::sqrt(2.0), 0.0), std::nextafter(1.0, 0.0), std::nextafter(1.0, 2.0)}) {
    x.push_back(special);
  }
  const std::vector<double> y = testing::run_probe(*device, testing::Probe::log, x);
  ASSERT_EQ(y.size(), x.size());
  double worst = 0.0;
  std::size_t worst_index = 0;
  std::size_t same_as_c = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double error =
        x[i] == 1.0 ? std::abs(y[i]) : ulps(y[i], std::log(static_cast<long double>(x[i])));
    if (error > worst) {
      worst = error;
      worst_index = i;
    }
    if (bits_of(y[i]) == bits_of(pk_log(x[i]))) ++same_as_c;
  }
  std::cout << "pk_log in GLSL: max error " << worst << " ulp over " << x.size()
            << " arguments (at x = " << x[worst_index] << "); " << same_as_c
            << " bit-identical to kernel_math.h's pk_log\n";
  RecordProperty("max_ulps", std::to_string(worst));
  EXPECT_LE(worst, 1.0) << "at x = " << x[worst_index];
  EXPECT_EQ(y[std::find(x.begin(), x.end(), 1.0) - x.begin()], 0.0) << "ln 1 must be exactly 0";
}

TEST(KernelMathGlsl, StepFactorPowerMatchesStdPow) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  std::mt19937_64 engine(7);
  std::uniform_real_distribution<double> exponent(-6.0, 4.0);
  std::vector<double> err;
  for (int i = 0; i < 200000; ++i) err.push_back(std::pow(10.0, exponent(engine)));
  for (double special : {1e-6, 1e4, 1.0, 0.5, 2.0, std::nextafter(1.0, 2.0)})
    err.push_back(special);
  const std::vector<double> y =
      testing::run_probe(*device, testing::Probe::pow_error_exponent, err);
  double worst = 0.0;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < err.size(); ++i) {
    const double error = ulps(y[i], std::pow(static_cast<long double>(err[i]),
                                             static_cast<long double>(PK_RK45_ERROR_EXPONENT)));
    if (error > worst) {
      worst = error;
      worst_index = i;
    }
  }
  std::cout << "pow(err, -0.2) in GLSL: max error " << worst << " ulp over " << err.size()
            << " arguments in [1e-6, 1e4]\n";
  EXPECT_LE(worst, 1.0) << "at err = " << err[worst_index];

  // Outside [1e-6, 1e4] only the side of the factor's clamp matters.
  const std::vector<double> outside = testing::run_probe(
      *device, testing::Probe::pow_error_exponent, {1e-300, 1e-9, 9.9e-7, 1.1e4, 1e9, 1e300});
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(PK_RK45_SAFETY * outside[i], PK_RK45_MAX_FACTOR) << "small error norm " << i;
  }
  for (std::size_t i = 3; i < 6; ++i) {
    EXPECT_LT(PK_RK45_SAFETY * outside[i], PK_RK45_MIN_FACTOR) << "large error norm " << i;
  }
}

}  // namespace
}  // namespace posekit::vulkan
