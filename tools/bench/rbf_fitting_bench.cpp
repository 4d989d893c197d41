// Benchmarks of the greedy RBF fit at the size pose correction meets (the lion: 5,000 vertices at
// 13 times, 65,000 constraints, about 2,700 centers, about 20 rounds of 128 centers).
//
// BM_BlockedUpdate/N: one round's blocked update, N centers -> N + 128 (assembly of the new rows on
//   the device, T = L^-1 C, W = D^-1 T, the Schur complement and its LU: the bordered block LDL^T).
// BM_FullRefactorization/N: what a round costs without it: assembling and factorizing the whole
//   system of N + 128 centers.
// BM_Fit/blocked, BM_Fit/full: a whole fit of the synthetic lion-sized problem; counters give the
//   centers and rounds reached and the seconds spent per stage.
// The second argument of each is the number of threads (0: all hardware threads), which bounds
// both the device and the dense linear algebra.
#include <posekit/cpu_device.hpp>
#include <posekit/rbf_fitting.hpp>

#include "correct/center_selection.hpp"
#include "correct/rbf_system.hpp"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <optional>

namespace posekit {
namespace {

using Eigen::Index;

constexpr Index kVertices = 5000;
constexpr int kTimes = 13;
constexpr Index kCentersPerRound = 128;

struct Problem {
  Points4 positions;
  Eigen::MatrixX3d values;
  double diagonal = 0;  // of the surface at t = 0
};

// A bumpy sphere that bends, twists about its vertical axis and turns as a whole while its center
// swings along a curve: vertex positions (x(t), t) and velocities x'(t) at kTimes times in [0, 1].
// The deformation has enough spatial detail that the fit needs a lion's worth of centers.
Eigen::Vector3d deformed(const Eigen::Vector3d& rest, double t) {
  const double s = std::sin(0.5 * M_PI * t);
  const double twist = 1.4 * s * rest.y();
  Eigen::Vector3d p(std::cos(twist) * rest.x() - std::sin(twist) * rest.z(), rest.y(),
                    std::sin(twist) * rest.x() + std::cos(twist) * rest.z());
  const double wave = std::sin(2.0 * M_PI * t);
  p += 0.12 * s *
       Eigen::Vector3d(std::sin(6.0 * rest.y() + 1.0), 0.6 * std::sin(7.0 * rest.z() + 0.5),
                       std::cos(6.0 * rest.x() - 0.3));
  p += 0.03 * wave *
       Eigen::Vector3d(std::cos(9.0 * rest.z()), std::sin(9.0 * rest.x() + 0.7), std::sin(8.0 * rest.y()));
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, 0.2).normalized();
  const Eigen::Vector3d center(0.3 * std::sin(2.0 * t), 0.2 * t * t, 0.1 * std::cos(3.0 * t));
  return center + Eigen::AngleAxisd(0.8 * std::sin(1.3 * t), axis) * p;
}

Problem lion_sized_problem() {
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3d> rest(static_cast<std::size_t>(kVertices));
  Eigen::MatrixX3d at_rest(kVertices, 3);
  for (Index k = 0; k < kVertices; ++k) {
    const double z = 1.0 - 2.0 * (static_cast<double>(k) + 0.5) / static_cast<double>(kVertices);
    const double r = std::sqrt(1.0 - z * z);
    const double turn = golden * static_cast<double>(k);
    const Eigen::Vector3d u(r * std::cos(turn), r * std::sin(turn), z);
    const double radius =
        0.6 * (1.0 + 0.2 * std::sin(3.0 * u.x()) * std::cos(2.0 * u.y() + u.z()));
    rest[static_cast<std::size_t>(k)] = radius * u;
    at_rest.row(k) = rest[static_cast<std::size_t>(k)].transpose();
  }
  Problem problem;
  problem.diagonal = (at_rest.colwise().maxCoeff() - at_rest.colwise().minCoeff()).norm();
  problem.positions.resize(kVertices * kTimes, 4);
  problem.values.resize(kVertices * kTimes, 3);
  const double h = 1e-5;  // central differences: truncation and round-off both near 1e-10
  for (int i = 0; i < kTimes; ++i) {
    const double t = static_cast<double>(i) / (kTimes - 1);
    for (Index k = 0; k < kVertices; ++k) {
      const Eigen::Vector3d& r = rest[static_cast<std::size_t>(k)];
      const Index row = i * kVertices + k;
      problem.positions.row(row) << deformed(r, t).transpose(), t;
      problem.values.row(row) = ((deformed(r, t + h) - deformed(r, t - h)) / (2.0 * h)).transpose();
    }
  }
  return problem;
}

const Problem& problem() {
  static const Problem instance = lion_sized_problem();
  return instance;
}

// Well-spread centers from the problem, as the fit would choose them.
const Points4& spread_centers() {
  static const Points4 centers = [] {
    const std::vector<Index> chosen = detail::spread_centers(problem().positions, 3072 + 2 * kCentersPerRound, 1e-9);
    Points4 rows(static_cast<Index>(chosen.size()), 4);
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      rows.row(static_cast<Index>(k)) = problem().positions.row(chosen[k]);
    }
    return rows;
  }();
  return centers;
}

std::optional<tbb::global_control> limit_threads(std::int64_t threads) {
  if (threads <= 0) return std::nullopt;
  return std::make_optional<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<std::size_t>(threads));
}

// Arguments: centers N before the round, threads.
void BM_BlockedUpdate(benchmark::State& state) {
  const Index n = state.range(0);
  const auto limit = limit_threads(state.range(1));
  const std::unique_ptr<Device> device = make_cpu_device(static_cast<int>(state.range(1)));
  const Points4& centers = spread_centers();
  detail::RbfSystem base(*device, true, n + kCentersPerRound);
  for (Index first = 0; first < n; first += kCentersPerRound) {
    base.add_centers(centers.middleRows(first, std::min(kCentersPerRound, n - first)));
  }
  const Points4 batch = centers.middleRows(n, kCentersPerRound);
  double assembly = 0;
  double factorization = 0;
  for (auto _ : state) {
    state.PauseTiming();
    detail::RbfSystem system = base;
    state.ResumeTiming();
    const detail::RbfSystemTimes times = system.add_centers(batch);
    assembly += times.assembly;
    factorization += times.factorization;
  }
  const auto per_iteration = benchmark::Counter::kAvgIterations;
  state.counters["assembly_s"] = benchmark::Counter(assembly, per_iteration);
  state.counters["factorization_s"] = benchmark::Counter(factorization, per_iteration);
}

void BM_FullRefactorization(benchmark::State& state) {
  const Index n = state.range(0);
  const auto limit = limit_threads(state.range(1));
  const std::unique_ptr<Device> device = make_cpu_device(static_cast<int>(state.range(1)));
  const Points4 all = spread_centers().topRows(n + kCentersPerRound);
  double assembly = 0;
  double factorization = 0;
  for (auto _ : state) {
    detail::RbfSystem system(*device, false);
    const detail::RbfSystemTimes times = system.add_centers(all);
    assembly += times.assembly;
    factorization += times.factorization;
  }
  const auto per_iteration = benchmark::Counter::kAvgIterations;
  state.counters["assembly_s"] = benchmark::Counter(assembly, per_iteration);
  state.counters["factorization_s"] = benchmark::Counter(factorization, per_iteration);
}

void apply_sizes(benchmark::internal::Benchmark* benchmark) {
  for (const std::int64_t threads : {1, 0}) {
    for (const std::int64_t n : {512, 1024, 2048, 2688, 3072}) benchmark->Args({n, threads});
  }
  benchmark->ArgNames({"centers", "threads"})->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_BlockedUpdate)->Apply(apply_sizes);
BENCHMARK(BM_FullRefactorization)->Apply(apply_sizes);

// Arguments: blocked update (1) or full refactorization (0), threads.
void BM_Fit(benchmark::State& state) {
  const auto limit = limit_threads(state.range(1));
  const std::unique_ptr<Device> device = make_cpu_device(static_cast<int>(state.range(1)));
  RbfFitOptions options;
  options.max_squared_error = 1e-4 * problem().diagonal;
  options.blocked_update = state.range(0) != 0;
  RbfFitReport report;
  for (auto _ : state) {
    fit_rbf_field(*device, problem().positions, problem().values, options, &report);
  }
  double assembly = 0;
  double factorization = 0;
  double evaluation = 0;
  for (const RbfFitRound& round : report.rounds) {
    assembly += round.assembly_seconds;
    factorization += round.factorization_seconds;
    evaluation += round.evaluation_seconds;
  }
  state.counters["constraints"] = static_cast<double>(problem().positions.rows());
  state.counters["centers"] = report.centers;
  state.counters["rounds"] = static_cast<double>(report.rounds.size());
  state.counters["converged"] = report.converged ? 1 : 0;
  state.counters["assembly_s"] = assembly;
  state.counters["factorization_s"] = factorization;
  state.counters["evaluation_s"] = evaluation;
}
BENCHMARK(BM_Fit)
    ->ArgNames({"blocked", "threads"})
    ->Args({1, 0})
    ->Args({0, 0})
    ->Args({1, 1})
    ->Args({0, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace posekit
