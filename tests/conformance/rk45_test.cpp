// Conformance cases of Device::integrate_rk45; conformance.hpp says how to add one.
//
// Three kinds of truth: closed-form flows of polynomial-only fields (the end positions must lie
// within the global error that the tolerances allow), the in-test reference integrator on random
// RBF fields (same decisions up to rounding: end positions close, step counts equal within one),
// and exact outcomes (statuses and counts of failures, empty batches, zero-length intervals).
#include "conformance.hpp"
#include "reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace posekit::conformance {
namespace {

// Adaptive steps keep each step's error near atol + rtol |x|; over the 10-100 steps of a run the
// errors add up and grow with the flow. 100 times the per-step tolerance bounds the global error of
// these smooth test flows with a wide margin (the CPU backend stays below 2 times) yet fails for a
// wrong coefficient, which moves the end positions by 1e-4 or more.
constexpr double kGlobalErrorFactor = 100.0;

// Where two correct integrators take the same steps their end positions agree to rounding; where
// rounding tips one accept/reject decision the other way, they differ by the global error, below
// the same bound.
constexpr double kReferenceFactor = kGlobalErrorFactor;

std::string format_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

::testing::AssertionResult positions_within(const Eigen::MatrixX3d& actual,
                                            const Eigen::MatrixX3d& expected,
                                            const Rk45Options& options, double factor) {
  const Tolerance tolerance{factor * options.absolute_tolerance,
                            factor * options.relative_tolerance};
  return expect_near(actual, expected, Eigen::MatrixXd(), tolerance);
}

// Every particle that finished took one evaluation to start and 6 per attempted step (the seventh
// stage of an accepted step is the first of the next).
::testing::AssertionResult first_same_as_last(const std::vector<Rk45ParticleStats>& stats) {
  for (std::size_t i = 0; i < stats.size(); ++i) {
    const Rk45ParticleStats& s = stats[i];
    if (s.status != Rk45Status::ok || s.accepted_steps == 0) continue;
    const int expected = 1 + 6 * (s.accepted_steps + s.rejected_steps);
    if (s.rhs_evaluations != expected) {
      return ::testing::AssertionFailure()
             << "particle " << i << ": " << s.rhs_evaluations << " field evaluations for "
             << s.accepted_steps << " accepted and " << s.rejected_steps
             << " rejected steps; Dormand-Prince with first-same-as-last takes " << expected;
    }
  }
  return ::testing::AssertionSuccess();
}

// Statuses equal; accepted and rejected counts equal within one (a decision tipped by rounding).
::testing::AssertionResult stats_match(const std::vector<Rk45ParticleStats>& actual,
                                       const std::vector<Rk45ParticleStats>& expected) {
  if (actual.size() != expected.size()) {
    return ::testing::AssertionFailure()
           << actual.size() << " statistics records for " << expected.size() << " particles";
  }
  for (std::size_t i = 0; i < actual.size(); ++i) {
    const Rk45ParticleStats& a = actual[i];
    const Rk45ParticleStats& b = expected[i];
    if (a.status != b.status || std::abs(a.accepted_steps - b.accepted_steps) > 1 ||
        std::abs(a.rejected_steps - b.rejected_steps) > 1) {
      return ::testing::AssertionFailure()
             << "particle " << i << ": status " << static_cast<int>(a.status) << ", "
             << a.accepted_steps << " accepted, " << a.rejected_steps << " rejected; reference: "
             << "status " << static_cast<int>(b.status) << ", " << b.accepted_steps << " accepted, "
             << b.rejected_steps << " rejected";
    }
  }
  return ::testing::AssertionSuccess();
}

// Runs the device on `start` inside sentinel rows; returns the end positions and statistics.
reference::Integration run_device(Device& device, const RbfField& field,
                                  const Eigen::MatrixX3d& start, const Rk45Options& options) {
  const std::unique_ptr<DeviceField> uploaded = device.upload_field(field);
  PaddedRows positions(start);
  reference::Integration result;
  result.stats = device.integrate_rk45(*uploaded, positions.inner(), options);
  EXPECT_TRUE(positions.untouched());
  EXPECT_EQ(result.stats.size(), static_cast<std::size_t>(start.rows()));
  result.positions = positions.value();
  return result;
}

Eigen::MatrixX3d random_start(std::uint64_t seed, Eigen::Index particles) {
  Random random(seed);
  return random.ball_points(particles).leftCols<3>();
}

// dx_i/dt = rate_i x_i + time_rate_i t + constant_i for each component on its own: a
// polynomial-only field (no centers) with a closed-form flow,
//   x(t) = (x0 - q(t0)) e^{rate (t - t0)} + q(t),  q(t) = -(time_rate t + constant) / rate
//                                                         - time_rate / rate^2,
// and x(t) = x0 + constant (t - t0) + time_rate (t^2 - t0^2) / 2 when rate = 0.
struct AffineFlowCase final : ConformanceCase {
  Eigen::Vector3d rate = Eigen::Vector3d::Zero();
  Eigen::Vector3d time_rate = Eigen::Vector3d::Zero();
  Eigen::Vector3d constant = Eigen::Vector3d::Zero();
  Eigen::Index particles = 7;
  std::uint64_t seed = 1;
  Rk45Options options;
  std::string label;


  std::string name() const override {
    return sanitize_name("rk45_" + label + "_particles" + std::to_string(particles) + "_seed" +
                         std::to_string(seed) + "_t" + format_number(options.t_begin) + "_to" +
                         format_number(options.t_end) + "_rtol" +
                         format_number(options.relative_tolerance));
  }

  RbfField field() const {
    RbfField field;
    field.centers.resize(0, 4);
    field.weights.resize(0, 3);
    for (int c = 0; c < 3; ++c) {
      field.polynomial(0, c) = constant(c);   // 1
      field.polynomial(1 + c, c) = rate(c);   // x, y or z
      field.polynomial(4, c) = time_rate(c);  // t
    }
    return field;
  }

  double exact(int c, double x0) const {
    const double t0 = options.t_begin;
    const double t1 = options.t_end;
    if (rate(c) == 0.0)
      return x0 + constant(c) * (t1 - t0) + time_rate(c) * (t1 * t1 - t0 * t0) / 2;
    const auto q = [&](double t) {
      return -(time_rate(c) * t + constant(c)) / rate(c) - time_rate(c) / (rate(c) * rate(c));
    };
    return (x0 - q(t0)) * std::exp(rate(c) * (t1 - t0)) + q(t1);
  }

  void run(Device& device) const override {
    const Eigen::MatrixX3d start = random_start(seed, particles);
    const reference::Integration actual = run_device(device, field(), start, options);
    Eigen::MatrixX3d truth(particles, 3);
    for (Eigen::Index i = 0; i < particles; ++i) {
      for (int c = 0; c < 3; ++c) truth(i, c) = exact(c, start(i, c));
    }
    EXPECT_TRUE(positions_within(actual.positions, truth, options, kGlobalErrorFactor));
    const reference::Integration expected = reference::integrate(field(), start, options);
    EXPECT_TRUE(stats_match(actual.stats, expected.stats));
    EXPECT_TRUE(first_same_as_last(actual.stats));
  }
};

// dx/dt = -omega y, dy/dt = omega x, dz/dt = 0: rotation about z by omega (t1 - t0). Exercises the
// off-diagonal polynomial coefficients.
struct RotationCase final : ConformanceCase {
  double omega = 1.0;
  Eigen::Index particles = 11;
  std::uint64_t seed = 1;
  Rk45Options options;


  std::string name() const override {
    return sanitize_name("rk45_rotation_omega" + format_number(omega) + "_particles" +
                         std::to_string(particles) + "_seed" + std::to_string(seed));
  }

  void run(Device& device) const override {
    RbfField field;
    field.centers.resize(0, 4);
    field.weights.resize(0, 3);
    field.polynomial(2, 0) = -omega;  // y in dx/dt
    field.polynomial(1, 1) = omega;   // x in dy/dt
    const Eigen::MatrixX3d start = random_start(seed, particles);
    const reference::Integration actual = run_device(device, field, start, options);
    const double angle = omega * (options.t_end - options.t_begin);
    Eigen::MatrixX3d truth = start;
    truth.col(0) = std::cos(angle) * start.col(0) - std::sin(angle) * start.col(1);
    truth.col(1) = std::sin(angle) * start.col(0) + std::cos(angle) * start.col(1);
    EXPECT_TRUE(positions_within(actual.positions, truth, options, kGlobalErrorFactor));
    EXPECT_TRUE(first_same_as_last(actual.stats));
    EXPECT_TRUE(stats_match(actual.stats, reference::integrate(field, start, options).stats));
  }
};

// A smooth random RBF field: centers in the unit ball x [0, 1], small weights, so that particles
// move by about 0.1-0.5 like vertices through a fitted correction field. The first `on_center`
// particles start exactly on a center (its time set to t_begin). Compared with the reference.
struct RandomFieldCase final : ConformanceCase {
  Eigen::Index particles = 0;
  Eigen::Index centers = 0;
  std::uint64_t seed = 1;
  double weight_scale = 0.02;
  Eigen::Index on_center = 0;
  Rk45Options options;


  std::string name() const override {
    std::string name = "rk45_random_field_particles" + std::to_string(particles) + "_centers" +
                       std::to_string(centers) + "_seed" + std::to_string(seed) + "_rtol" +
                       format_number(options.relative_tolerance);
    if (on_center > 0) name += "_on_center" + std::to_string(on_center);
    return sanitize_name(name);
  }

  void run(Device& device) const override {
    Random random(seed);
    Points4 center_set = random.ball_points(centers);
    Eigen::MatrixX3d start = random.ball_points(particles).leftCols<3>();
    for (Eigen::Index i = 0; i < std::min(on_center, std::min(particles, centers)); ++i) {
      center_set(i, 3) = options.t_begin;
      start.row(i) = center_set.row(i).leftCols<3>();
    }
    const RbfField field = random.field(center_set, weight_scale, weight_scale);
    const reference::Integration actual = run_device(device, field, start, options);
    const reference::Integration expected = reference::integrate(field, start, options);
    EXPECT_TRUE(positions_within(actual.positions, expected.positions, options, kReferenceFactor));
    EXPECT_TRUE(stats_match(actual.stats, expected.stats));
    EXPECT_TRUE(first_same_as_last(actual.stats));
    const double moved = (expected.positions - start).rowwise().norm().maxCoeff();
    EXPECT_GT(moved, 1e-3) << "the test field should move the particles";
  }
};

// Outcomes that are exact whatever the rounding: failures reported in the statistics (never thrown,
// positions left where the particle stopped), a zero-length interval and an empty batch.
enum class Outcome { max_steps, step_underflow, non_finite, zero_interval, empty_batch };

struct OutcomeCase final : ConformanceCase {
  Outcome outcome = Outcome::max_steps;


  std::string name() const override {
    switch (outcome) {
      case Outcome::max_steps: return "rk45_outcome_max_steps";
      case Outcome::step_underflow: return "rk45_outcome_step_underflow";
      case Outcome::non_finite: return "rk45_outcome_non_finite";
      case Outcome::zero_interval: return "rk45_outcome_zero_interval";
      case Outcome::empty_batch: return "rk45_outcome_empty_batch";
    }
    return "rk45_outcome_unknown";
  }

  void run(Device& device) const override {
    // The rotation field of RotationCase with omega = 1, plus a few centers.
    Random random(7);
    RbfField field = random.field(random.ball_points(5), 0.01, 0.0);
    field.polynomial(2, 0) = -1.0;
    field.polynomial(1, 1) = 1.0;
    Eigen::MatrixX3d start = random_start(8, 5);
    Rk45Options options;

    switch (outcome) {
      case Outcome::max_steps: {
        // Steps grow from 1e-3 by at most 10 each: 4 attempts cannot reach t = 1.
        options.initial_step = 1e-3;
        options.max_steps = 4;
        const reference::Integration actual = run_device(device, field, start, options);
        for (const Rk45ParticleStats& s : actual.stats) {
          EXPECT_EQ(s.status, Rk45Status::max_steps);
          EXPECT_EQ(s.accepted_steps + s.rejected_steps, 4);
          EXPECT_EQ(s.rhs_evaluations, 1 + 6 * 4);
        }
        EXPECT_TRUE(actual.positions.allFinite());
        EXPECT_FALSE(actual.positions.isApprox(start)) << "accepted steps must move the particles";
        break;
      }
      case Outcome::step_underflow: {
        // A step of 0.5 misses tolerances of 1e-13 by far: the rejected step shrinks at most to
        // 0.2 x 0.5 = 0.1, below min_step = 0.3.
        options.relative_tolerance = 1e-13;
        options.absolute_tolerance = 1e-15;
        options.initial_step = 0.5;
        options.min_step = 0.3;
        const reference::Integration actual = run_device(device, field, start, options);
        for (const Rk45ParticleStats& s : actual.stats) {
          EXPECT_EQ(s.status, Rk45Status::step_underflow);
          EXPECT_EQ(s.accepted_steps, 0);
          EXPECT_EQ(s.rejected_steps, 1);
          EXPECT_EQ(s.rhs_evaluations, 7);
        }
        EXPECT_EQ(actual.positions, start) << "no step was accepted";
        break;
      }
      case Outcome::non_finite: {
        // A NaN weight makes every field value NaN, from the very first evaluation on.
        field.weights(2, 1) = std::numeric_limits<double>::quiet_NaN();
        const reference::Integration actual = run_device(device, field, start, options);
        for (const Rk45ParticleStats& s : actual.stats) {
          EXPECT_EQ(s.status, Rk45Status::non_finite);
          EXPECT_EQ(s.accepted_steps, 0);
          EXPECT_EQ(s.rejected_steps, 0);
          EXPECT_EQ(s.rhs_evaluations, 1);
        }
        EXPECT_EQ(actual.positions, start);
        EXPECT_EQ(summarize(actual.stats).failures, start.rows());
        break;
      }
      case Outcome::zero_interval: {
        options.t_begin = 0.25;
        options.t_end = 0.25;
        const reference::Integration actual = run_device(device, field, start, options);
        for (const Rk45ParticleStats& s : actual.stats) {
          EXPECT_EQ(s.status, Rk45Status::ok);
          EXPECT_EQ(s.accepted_steps + s.rejected_steps + s.rhs_evaluations, 0);
        }
        EXPECT_EQ(actual.positions, start);
        break;
      }
      case Outcome::empty_batch: {
        const reference::Integration actual =
            run_device(device, field, Eigen::MatrixX3d(0, 3), options);
        EXPECT_TRUE(actual.stats.empty());
        break;
      }
    }
  }
};

std::shared_ptr<const ConformanceCase> affine(const std::string& label, const Eigen::Vector3d& rate,
                                              const Eigen::Vector3d& time_rate,
                                              const Eigen::Vector3d& constant,
                                              Eigen::Index particles, std::uint64_t seed,
                                              double t_begin, double t_end, double rtol,
                                              double atol) {
  auto c = std::make_shared<AffineFlowCase>();
  c->label = label;
  c->rate = rate;
  c->time_rate = time_rate;
  c->constant = constant;
  c->particles = particles;
  c->seed = seed;
  c->options.t_begin = t_begin;
  c->options.t_end = t_end;
  c->options.relative_tolerance = rtol;
  c->options.absolute_tolerance = atol;
  return c;
}

std::shared_ptr<const ConformanceCase> random_field(Eigen::Index particles, Eigen::Index centers,
                                                    std::uint64_t seed, double rtol, double atol,
                                                    Eigen::Index on_center = 0) {
  auto c = std::make_shared<RandomFieldCase>();
  c->particles = particles;
  c->centers = centers;
  c->seed = seed;
  c->on_center = on_center;
  c->options.relative_tolerance = rtol;
  c->options.absolute_tolerance = atol;
  return c;
}

std::shared_ptr<const ConformanceCase> outcome(Outcome kind) {
  auto c = std::make_shared<OutcomeCase>();
  c->outcome = kind;
  return c;
}

}  // namespace

CaseList rk45_cases() {
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  CaseList cases = {
      // f = (t, 0, 0): x(t) = x0 + t^2 / 2.
      affine("time_only", zero, Eigen::Vector3d(1, 0, 0), zero, 5, 1, 0.0, 1.0, 1e-7, 1e-9),
      // f = (a x, b y, c z): x(t) = exp(a t) x0 ...
      affine("exponential", Eigen::Vector3d(0.5, -1.0, 2.0), zero, zero, 13, 2, 0.0, 1.0, 1e-7,
             1e-9),
      affine("exponential", Eigen::Vector3d(0.5, -1.0, 2.0), zero, zero, 13, 3, 0.0, 1.0, 1e-11,
             1e-13),
      // f = (a x + t, b y, c z + 1), backwards from t = 1 to t = 0.
      affine("affine_backward", Eigen::Vector3d(0.5, -1.0, 2.0), Eigen::Vector3d(1, 0, 0),
             Eigen::Vector3d(0, 0, 1), 7, 4, 1.0, 0.0, 1e-9, 1e-11),
      affine("affine_interval", Eigen::Vector3d(-0.3, 0.7, 0.0), Eigen::Vector3d(0, 2, 1),
             Eigen::Vector3d(1, 0, -1), 1, 5, 0.2, 0.7, 1e-8, 1e-10),
  };
  auto rotation = std::make_shared<RotationCase>();
  rotation->omega = 3.0;
  rotation->particles = 11;
  rotation->seed = 6;
  rotation->options.relative_tolerance = 1e-9;
  rotation->options.absolute_tolerance = 1e-11;
  cases.push_back(rotation);

  cases.push_back(random_field(1, 1, 7, 1e-7, 1e-9));
  cases.push_back(random_field(13, 11, 8, 1e-7, 1e-9));
  cases.push_back(random_field(37, 257, 9, 1e-9, 1e-11));
  cases.push_back(random_field(5, 1031, 10, 1e-7, 1e-9));
  cases.push_back(random_field(11, 13, 11, 1e-7, 1e-9, 3));

  for (Outcome kind : {Outcome::max_steps, Outcome::step_underflow, Outcome::non_finite,
                       Outcome::zero_interval, Outcome::empty_batch}) {
    cases.push_back(outcome(kind));
  }
  return cases;
}

}  // namespace posekit::conformance
