// The RK45 kernel's per-particle state machine (kernels/cuda/rk45_particle.cuh), compiled for the
// host: driven one field evaluation at a time, it must take exactly the decisions of
// PK_RK45_INTEGRATE_PARTICLE, the loop every other backend runs, down to the last bit of the end
// position and every count. Runs on any machine; the kernel itself is held against the reference
// by the conformance suite where a GPU is present.
#include "cuda/rk45_particle.cuh"

#include "conformance.hpp"

#include <posekit/device.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

namespace posekit::cuda {
namespace {

// f(point) summed in the order of the centers, then the polynomial: a plain host field.
struct HostField {
  RbfField field;
  void operator()(const double* point, double* value) const {
    for (int c = 0; c < 3; ++c) value[c] = 0.0;
    for (Eigen::Index j = 0; j < field.centers.rows(); ++j) {
      const double phi = pk_phi_from_squared_distance(pk_squared_distance(
          point[0] - field.centers(j, 0), point[1] - field.centers(j, 1),
          point[2] - field.centers(j, 2), point[3] - field.centers(j, 3)));
      for (int c = 0; c < 3; ++c) value[c] += phi * field.weights(j, c);
    }
    for (int c = 0; c < 3; ++c) {
      value[c] += pk_polynomial_value(field.polynomial.col(c).data(), point[0], point[1],
                                      point[2], point[3]);
    }
  }
};

struct Outcome {
  double x[3];
  pk_rk45_controller controller;
  int evaluations = 0;  // calls of the field
};

Outcome with_macro(const HostField& field, const double* start, const Rk45Options& o) {
  Outcome out;
  for (int c = 0; c < 3; ++c) out.x[c] = start[c];
  pk_rk45_begin(&out.controller, o.t_begin, o.t_end, o.relative_tolerance, o.absolute_tolerance,
                o.initial_step, o.min_step, o.max_steps);
  const auto evaluate = [&](const double* point, double* value) {
    ++out.evaluations;
    field(point, value);
  };
  PK_RK45_INTEGRATE_PARTICLE(out.controller, out.x, evaluate);
  return out;
}

Outcome with_state_machine(const HostField& field, const double* start, const Rk45Options& o) {
  Rk45Particle p;
  Outcome out;
  bool running = rk45_start(p, start, o.t_begin, o.t_end, o.relative_tolerance,
                            o.absolute_tolerance, o.initial_step, o.min_step, o.max_steps);
  while (running) {
    double point[4];
    double value[3];
    rk45_evaluation_point(p, point);
    field(point, value);
    ++out.evaluations;
    rk45_consume_evaluation(p, value);
    running = p.controller.status == PK_RK45_RUNNING;
  }
  for (int c = 0; c < 3; ++c) out.x[c] = p.x[c];
  out.controller = p.controller;
  return out;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

::testing::AssertionResult same_outcome(const Outcome& a, const Outcome& b) {
  for (int c = 0; c < 3; ++c) {
    if (!same_bits(a.x[c], b.x[c])) {
      return ::testing::AssertionFailure() << "component " << c << ": " << a.x[c] << " vs " << b.x[c];
    }
  }
  const pk_rk45_controller& s = a.controller;
  const pk_rk45_controller& m = b.controller;
  if (s.status != m.status || s.accepted_steps != m.accepted_steps ||
      s.rejected_steps != m.rejected_steps || s.rhs_evaluations != m.rhs_evaluations ||
      a.evaluations != b.evaluations || !same_bits(s.t, m.t) || !same_bits(s.h, m.h)) {
    return ::testing::AssertionFailure()
           << "state machine: status " << s.status << ", " << s.accepted_steps << " accepted, "
           << s.rejected_steps << " rejected, " << s.rhs_evaluations << " counted and "
           << a.evaluations << " made evaluations, t " << s.t << "; macro: status " << m.status
           << ", " << m.accepted_steps << " accepted, " << m.rejected_steps << " rejected, "
           << m.rhs_evaluations << " counted and " << b.evaluations << " made evaluations, t "
           << m.t;
  }
  return ::testing::AssertionSuccess();
}

void expect_same_for_every_particle(const HostField& field, const Eigen::MatrixX3d& start,
                                    const Rk45Options& options, const std::string& label) {
  for (Eigen::Index i = 0; i < start.rows(); ++i) {
    const double x[3] = {start(i, 0), start(i, 1), start(i, 2)};
    EXPECT_TRUE(same_outcome(with_state_machine(field, x, options), with_macro(field, x, options)))
        << label << ", particle " << i;
  }
}

TEST(Rk45StateMachine, TakesTheMacrosStepsThroughRandomFields) {
  conformance::Random random(41);
  for (const Eigen::Index centers : {0, 1, 13, 257}) {
    HostField field{random.field(random.ball_points(centers), 0.02, 0.02)};
    const Eigen::MatrixX3d start = random.ball_points(11).leftCols<3>();
    for (const double rtol : {1e-5, 1e-7, 1e-10}) {
      Rk45Options options;
      options.relative_tolerance = rtol;
      options.absolute_tolerance = rtol * 1e-2;
      expect_same_for_every_particle(field, start, options,
                                     std::to_string(centers) + " centers, rtol " +
                                         std::to_string(rtol));
    }
  }
}

TEST(Rk45StateMachine, RejectsStepsAsTheMacroDoes) {
  // A fast rotation with a large first step: the first attempts are rejected.
  conformance::Random random(42);
  HostField field{random.field(random.ball_points(5), 0.01, 0.0)};
  field.field.polynomial(2, 0) = -20.0;
  field.field.polynomial(1, 1) = 20.0;
  Rk45Options options;
  options.initial_step = 0.5;
  const Eigen::MatrixX3d start = random.ball_points(7).leftCols<3>();
  expect_same_for_every_particle(field, start, options, "rotation");
  const double x[3] = {start(0, 0), start(0, 1), start(0, 2)};
  EXPECT_GT(with_state_machine(field, x, options).controller.rejected_steps, 0);
}

TEST(Rk45StateMachine, EndsAsTheMacroDoes) {
  conformance::Random random(43);
  HostField field{random.field(random.ball_points(5), 0.01, 0.01)};
  const Eigen::MatrixX3d start = random.ball_points(3).leftCols<3>();

  Rk45Options backward;
  backward.t_begin = 1.0;
  backward.t_end = 0.2;
  expect_same_for_every_particle(field, start, backward, "backward");

  Rk45Options max_steps;
  max_steps.initial_step = 1e-3;
  max_steps.max_steps = 4;
  expect_same_for_every_particle(field, start, max_steps, "max_steps");

  Rk45Options underflow;
  underflow.relative_tolerance = 1e-13;
  underflow.absolute_tolerance = 1e-15;
  underflow.initial_step = 0.5;
  underflow.min_step = 0.3;
  expect_same_for_every_particle(field, start, underflow, "step_underflow");

  Rk45Options zero_interval;
  zero_interval.t_begin = zero_interval.t_end = 0.25;
  expect_same_for_every_particle(field, start, zero_interval, "zero interval");
  const double x[3] = {start(0, 0), start(0, 1), start(0, 2)};
  EXPECT_EQ(with_state_machine(field, x, zero_interval).evaluations, 0);

  HostField broken = field;
  broken.field.weights(2, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_same_for_every_particle(broken, start, Rk45Options(), "non-finite");
  EXPECT_EQ(with_state_machine(broken, x, Rk45Options()).controller.status, PK_RK45_NON_FINITE);
}

}  // namespace
}  // namespace posekit::cuda
