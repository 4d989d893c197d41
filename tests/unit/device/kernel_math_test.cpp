// kernel_math.h, the formulas every backend shares: the logarithm's accuracy, phi, the polynomial
// basis order, the Dormand-Prince tableau and the step-size control.
#include "common/kernel_math.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

namespace {

// Error of pk_log(x) in units in the last place of the exact result. With an 80-bit or wider long
// double, logl is exact to far below a double ulp; elsewhere std::log itself errs by up to 0.5 ulp.
constexpr bool kExtendedReference = std::numeric_limits<long double>::digits >= 64;
constexpr double kMaxUlp = kExtendedReference ? 1.0 : 1.5;

double ulp_error(double x) {
  const long double exact = std::log(static_cast<long double>(x));
  const auto rounded = static_cast<double>(exact);
  const double magnitude = std::abs(rounded);
  const double ulp = std::nextafter(magnitude, std::numeric_limits<double>::infinity()) - magnitude;
  return static_cast<double>(std::abs(static_cast<long double>(pk_log(x)) - exact) / ulp);
}

// Passes when pk_log is within kMaxUlp at every x; names the worst.
::testing::AssertionResult log_accurate(const std::vector<double>& arguments) {
  double worst = 0.0;
  double worst_at = 0.0;
  for (const double x : arguments) {
    const double error = ulp_error(x);
    if (!(error <= worst)) {
      worst = error;
      worst_at = x;
    }
  }
  if (worst <= kMaxUlp) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "pk_log(" << worst_at << ") is off by " << worst << " ulp (allowed " << kMaxUlp << ")";
}

TEST(KernelLog, WithinOneUlpFrom1e300To1e300) {
  std::mt19937_64 engine(20240601);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  std::vector<double> arguments;
  arguments.reserve(1000000);
  for (int i = 0; i < 1000000; ++i) arguments.push_back(std::pow(10.0, exponent(engine)));
  EXPECT_TRUE(log_accurate(arguments));
}

TEST(KernelLog, WithinOneUlpAtPowersOfTwoAndTheirNeighbours) {
  std::vector<double> arguments;
  for (int e = DBL_MIN_EXP - 1; e < DBL_MAX_EXP; ++e) {
    const double x = std::ldexp(1.0, e);
    arguments.push_back(x);
    arguments.push_back(std::nextafter(x, 0.0));
    arguments.push_back(std::nextafter(x, 2 * x));
    // Either side of sqrt(2) * 2^e, where the mantissa reduction switches its exponent.
    const double switch_point = std::ldexp(std::sqrt(2.0), e);
    arguments.push_back(std::nextafter(switch_point, 0.0));
    arguments.push_back(switch_point);
    arguments.push_back(std::nextafter(switch_point, 2 * switch_point));
  }
  arguments.push_back(DBL_MIN);
  arguments.push_back(DBL_MAX);
  arguments.erase(std::remove_if(arguments.begin(), arguments.end(),
                                 [](double x) { return !(x >= DBL_MIN && x <= DBL_MAX); }),
                  arguments.end());
  EXPECT_TRUE(log_accurate(arguments));
}

TEST(KernelLog, WithinOneUlpNearOne) {
  std::vector<double> arguments;
  for (int k = 1; k <= 100000; ++k) {
    arguments.push_back(1.0 + k * DBL_EPSILON);
    arguments.push_back(1.0 - k * DBL_EPSILON / 2);
  }
  for (int digits = 1; digits <= 15; ++digits) {
    arguments.push_back(1.0 + std::pow(10.0, -digits));
    arguments.push_back(1.0 - std::pow(10.0, -digits));
  }
  std::mt19937_64 engine(7);
  std::uniform_real_distribution<double> near_one(0.7, 1.5);
  for (int i = 0; i < 200000; ++i) arguments.push_back(near_one(engine));
  EXPECT_TRUE(log_accurate(arguments));
  EXPECT_EQ(pk_log(1.0), 0.0);
}

// The documented domain ends at the positive normal numbers; phi never leaves it but carries
// inf and NaN through its factor r2.
TEST(KernelLog, OutsideTheDomainPhiStillPropagatesInfAndNan) {
  EXPECT_TRUE(std::isfinite(pk_log(std::numeric_limits<double>::infinity())));
  EXPECT_EQ(pk_phi_from_squared_distance(std::numeric_limits<double>::infinity()),
            std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(pk_phi_from_squared_distance(std::numeric_limits<double>::quiet_NaN())));
}

TEST(KernelPhi, IsZeroAtZeroAndAtOne) {
  EXPECT_EQ(pk_phi_from_squared_distance(0.0), 0.0);
  EXPECT_EQ(pk_phi_from_squared_distance(1.0), 0.0);
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_LE(std::abs(pk_phi_from_squared_distance(tiny)), 1e-320);
}

TEST(KernelPhi, IsRSquaredLogR) {
  std::mt19937_64 engine(11);
  std::uniform_real_distribution<double> exponent(-6.0, 3.0);
  for (int i = 0; i < 10000; ++i) {
    const double r = std::pow(10.0, exponent(engine));
    const double r2 = r * r;
    const long double expected = 0.5L * r2 * std::log(static_cast<long double>(r2));
    const double actual = pk_phi_from_squared_distance(r2);
    // A few ulp of phi, or of r2 where phi passes through zero at r = 1.
    EXPECT_LE(std::abs(actual - expected),
              4 * DBL_EPSILON * std::max<long double>(std::abs(expected), r2))
        << "r = " << r;
  }
}

TEST(KernelPhi, SquaredDistanceAddsTheFourSquares) {
  EXPECT_EQ(pk_squared_distance(1.0, -2.0, 3.0, 0.5), 14.25);
  EXPECT_EQ(pk_squared_distance(0.0, 0.0, 0.0, 0.0), 0.0);
}

TEST(KernelPolynomial, BasisOrderIsConstantLinearThenProducts) {
  // Distinct primes make every product distinct, so each slot is identified.
  const double x = 2, y = 3, z = 5, t = 7;
  double basis[PK_POLYNOMIAL_TERMS];
  pk_polynomial_basis(x, y, z, t, basis);
  const double expected[PK_POLYNOMIAL_TERMS] = {
      1, x, y, z, t, x * x, x * y, x * z, x * t, y * y, y * z, y * t, z * z, z * t, t * t};
  for (int k = 0; k < PK_POLYNOMIAL_TERMS; ++k) EXPECT_EQ(basis[k], expected[k]) << "term " << k;
}

TEST(KernelPolynomial, ValueWeighsEachTermByItsCoefficient) {
  double basis[PK_POLYNOMIAL_TERMS];
  pk_polynomial_basis(0.5, -1.5, 2.0, 0.25, basis);
  for (int k = 0; k < PK_POLYNOMIAL_TERMS; ++k) {
    double coefficients[PK_POLYNOMIAL_TERMS] = {};
    coefficients[k] = 3.0;
    EXPECT_EQ(pk_polynomial_value(coefficients, 0.5, -1.5, 2.0, 0.25), 3.0 * basis[k]) << k;
  }
}

// The tableau against the order conditions it must satisfy: any typo in a coefficient breaks one.
TEST(KernelTableau, SatisfiesTheOrderConditions) {
  const double c[7] = {0.0, PK_DP_C2, PK_DP_C3, PK_DP_C4, PK_DP_C5, PK_DP_C6, PK_DP_C7};
  const double a[7][6] = {{0, 0, 0, 0, 0, 0},
                          {PK_DP_A21, 0, 0, 0, 0, 0},
                          {PK_DP_A31, PK_DP_A32, 0, 0, 0, 0},
                          {PK_DP_A41, PK_DP_A42, PK_DP_A43, 0, 0, 0},
                          {PK_DP_A51, PK_DP_A52, PK_DP_A53, PK_DP_A54, 0, 0},
                          {PK_DP_A61, PK_DP_A62, PK_DP_A63, PK_DP_A64, PK_DP_A65, 0},
                          {PK_DP_B1, 0, PK_DP_B3, PK_DP_B4, PK_DP_B5, PK_DP_B6}};
  const double b[7] = {PK_DP_B1, 0, PK_DP_B3, PK_DP_B4, PK_DP_B5, PK_DP_B6, 0};
  const double e[7] = {PK_DP_E1, 0, PK_DP_E3, PK_DP_E4, PK_DP_E5, PK_DP_E6, PK_DP_E7};
  double embedded[7];
  for (int i = 0; i < 7; ++i) embedded[i] = b[i] - e[i];
  const double tolerance = 1e-14;

  for (int i = 0; i < 7; ++i) {
    double row = 0;
    for (int j = 0; j < 6; ++j) row += a[i][j];
    EXPECT_NEAR(row, c[i], tolerance) << "row " << i + 1 << " of A must sum to c";
  }
  for (int q = 0; q <= 4; ++q) {
    double fifth = 0, fourth = 0;
    for (int i = 0; i < 7; ++i) {
      fifth += b[i] * std::pow(c[i], q);
      fourth += embedded[i] * std::pow(c[i], q);
    }
    EXPECT_NEAR(fifth, 1.0 / (q + 1), tolerance) << "sum b c^" << q;
    if (q <= 3) {
      EXPECT_NEAR(fourth, 1.0 / (q + 1), tolerance) << "sum b* c^" << q;
    }
  }
  // Two of the conditions that involve A itself.
  double bac = 0, bac2 = 0;
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 6; ++j) {
      bac += b[i] * a[i][j] * c[j];
      bac2 += b[i] * a[i][j] * c[j] * c[j];
    }
  }
  EXPECT_NEAR(bac, 1.0 / 6, tolerance);
  EXPECT_NEAR(bac2, 1.0 / 12, tolerance);
}

TEST(KernelStepControl, FactorsFollowTheDocumentedRule) {
  EXPECT_EQ(pk_rk45_accept_factor(0.0, 0), PK_RK45_MAX_FACTOR);
  EXPECT_EQ(pk_rk45_accept_factor(1e-12, 0), PK_RK45_MAX_FACTOR);
  EXPECT_DOUBLE_EQ(pk_rk45_accept_factor(1.0, 0), PK_RK45_SAFETY);
  EXPECT_DOUBLE_EQ(pk_rk45_accept_factor(0.5, 0), 0.9 * std::pow(0.5, -0.2));
  EXPECT_EQ(pk_rk45_accept_factor(1e-12, 1), 1.0) << "no growth right after a rejection";
  EXPECT_DOUBLE_EQ(pk_rk45_accept_factor(1.0, 1), PK_RK45_SAFETY);
  EXPECT_DOUBLE_EQ(pk_rk45_reject_factor(2.0), 0.9 * std::pow(2.0, -0.2));
  EXPECT_EQ(pk_rk45_reject_factor(1e12), PK_RK45_MIN_FACTOR);
}

TEST(KernelStepControl, ErrorNormIsTheRootMeanSquareOfScaledErrors) {
  double k[3 * PK_DP_STAGES] = {};
  k[18] = 1.0;  // only k7 in x: error_x = h * E7
  const double x[3] = {2.0, 0.0, 0.0};
  const double x_new[3] = {-4.0, 0.0, 0.0};
  const double h = 0.5;
  const double scale = 1e-9 + 1e-6 * 4.0;  // atol + rtol * max(|x|, |x_new|)
  EXPECT_DOUBLE_EQ(pk_rk45_error_norm(h, x, x_new, k, 1e-6, 1e-9),
                   std::abs(h * PK_DP_E7 / scale) / std::sqrt(3.0));
}

TEST(KernelStepControl, LastStepIsStretchedOrShortenedToEndExactly) {
  pk_rk45_controller c;
  pk_rk45_begin(&c, 0.5, 1.0, 1e-7, 1e-9, 0.496, 1e-12, 100);
  EXPECT_EQ(pk_rk45_trial_step(&c), 0.5) << "within 1% of the end: stretched";
  EXPECT_TRUE(c.reaches_end);
  c.h = 0.49;
  EXPECT_EQ(pk_rk45_trial_step(&c), 0.49);
  EXPECT_FALSE(c.reaches_end);
  c.h = 3.0;
  EXPECT_EQ(pk_rk45_trial_step(&c), 0.5) << "beyond the end: shortened";

  pk_rk45_begin(&c, 1.0, 0.25, 1e-7, 1e-9, 0.1, 1e-12, 100);
  EXPECT_EQ(pk_rk45_trial_step(&c), -0.1) << "backwards in time";
  EXPECT_EQ(pk_rk45_stage_time(&c, 2, -0.1), 1.0 - 0.1 * PK_DP_C2);

  pk_rk45_begin(&c, 0.3, 0.3, 1e-7, 1e-9, 0.1, 1e-12, 100);
  EXPECT_EQ(c.status, PK_RK45_OK) << "an empty interval is done before it starts";
}

// dx/dt = x, dy/dt = -2 y, dz/dt = t through the shared driver macro.
#define EXPONENTIAL_FIELD(point, derivative) \
  do {                                       \
    (derivative)[0] = (point)[0];            \
    (derivative)[1] = -2.0 * (point)[1];     \
    (derivative)[2] = (point)[3];            \
    ++evaluations;                           \
  } while (0)

TEST(KernelDriver, IntegratesAnExponentialFlowWithSixEvaluationsPerStep) {
  pk_rk45_controller c;
  pk_rk45_begin(&c, 0.0, 2.0, 1e-10, 1e-12, 0.01, 1e-12, 10000);
  double x[3] = {1.0, 1.0, 0.5};
  int evaluations = 0;
  PK_RK45_INTEGRATE_PARTICLE(c, x, EXPONENTIAL_FIELD);
  EXPECT_EQ(c.status, PK_RK45_OK);
  EXPECT_EQ(c.t, 2.0);
  EXPECT_NEAR(x[0], std::exp(2.0), 100 * 1e-10 * std::exp(2.0));
  EXPECT_NEAR(x[1], std::exp(-4.0), 100 * (1e-12 + 1e-10 * std::exp(-4.0)));
  EXPECT_NEAR(x[2], 0.5 + 2.0, 100 * 1e-10 * 2.5);
  EXPECT_EQ(evaluations, c.rhs_evaluations);
  EXPECT_EQ(c.rhs_evaluations, 1 + 6 * (c.accepted_steps + c.rejected_steps));
  EXPECT_GT(c.accepted_steps, 5);
}

TEST(KernelDriver, StopsAtMaxSteps) {
  pk_rk45_controller c;
  pk_rk45_begin(&c, 0.0, 1.0, 1e-10, 1e-12, 1e-6, 1e-12, 3);
  double x[3] = {1.0, 1.0, 0.0};
  int evaluations = 0;
  PK_RK45_INTEGRATE_PARTICLE(c, x, EXPONENTIAL_FIELD);
  EXPECT_EQ(c.status, PK_RK45_MAX_STEPS);
  EXPECT_EQ(c.accepted_steps + c.rejected_steps, 3);
  EXPECT_EQ(evaluations, 1 + 6 * 3);
}

// Every constant a generator would emit survives printing with 17 significant digits.
TEST(KernelConstants, RoundTripThroughSeventeenDigits) {
  int count = 0;
#define ROUND_TRIP(name)                                                       \
  {                                                                            \
    char text[64];                                                             \
    std::snprintf(text, sizeof text, "%.17g", static_cast<double>(name));      \
    EXPECT_EQ(std::strtod(text, nullptr), static_cast<double>(name)) << #name; \
    ++count;                                                                   \
  }
  PK_KERNEL_DOUBLE_CONSTANTS(ROUND_TRIP)
#undef ROUND_TRIP
  EXPECT_EQ(count, 48);
#define COUNT(name) ++count;
  PK_KERNEL_WORD_CONSTANTS(COUNT)
#undef COUNT
  EXPECT_EQ(count, 48 + 10);
}

// The decimal spellings are exactly fdlibm's coefficients (their bit patterns are in e_log.c).
TEST(KernelConstants, LogCoefficientsAreExactlyFdlibms) {
  EXPECT_EQ(pk_bits_of(PK_LOG_LN2_HI), 0x3fe62e42fee00000ULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LN2_LO), 0x3dea39ef35793c76ULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG1), 0x3fe5555555555593ULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG2), 0x3fd999999997fa04ULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG3), 0x3fd2492494229359ULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG4), 0x3fcc71c51d8e78afULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG5), 0x3fc7466496cb03deULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG6), 0x3fc39a09d078c69fULL);
  EXPECT_EQ(pk_bits_of(PK_LOG_LG7), 0x3fc2f112df3e5244ULL);
  EXPECT_EQ(pk_double_from_bits(pk_bits_of(0.1)), 0.1);
}

TEST(KernelConstants, FinitenessIsReadFromTheBits) {
  EXPECT_TRUE(pk_is_finite(0.0));
  EXPECT_TRUE(pk_is_finite(-DBL_MAX));
  EXPECT_TRUE(pk_is_finite(std::numeric_limits<double>::denorm_min()));
  EXPECT_FALSE(pk_is_finite(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(pk_is_finite(-std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(pk_is_finite(std::numeric_limits<double>::quiet_NaN()));
}

}  // namespace
