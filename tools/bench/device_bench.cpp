// Benchmarks of the device operations at the sizes pose correction meets: ~65,000 constraints
// against ~2,700 centers, 5,000 vertices integrated through the fitted field.
//  - BM_RbfEvaluation, BM_RbfAssembly, BM_Rk45Batch: the CPU backend, with every compiled
//    instruction set and thread count side by side.
//  - BM_Backend<Operation>/<backend>: the same work on every backend the registry lists as
//    available here (registered at start-up), so that one run gives the ratios between backends.
//    Each backend's device is created once, before timing (GPU backends build their programs then).
//  - BM_CreateAutoDevice, BM_CreateCpuDevice: the registry's choice of a device and its creation.
//
// Counters: evaluations/s = points x centers per second of wall time (the kernel phi evaluations);
// for RK45 the field evaluations per particle and how far the particles moved. The backends' RBF
// evaluation also reports fp64_flop/s, kFlopsPerTerm per evaluation, for a comparison with a
// device's fp64 peak (posekit devices prints it for CUDA GPUs).
#include <posekit/cpu_device.hpp>
#include <posekit/device_registry.hpp>

#include "cpu/cpu_device.hpp"
#include "cpu/kernel_isa.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <exception>
#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace posekit {
namespace {

Points4 ball_points(std::mt19937_64& engine, Eigen::Index count) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Points4 points(count, 4);
  for (Eigen::Index i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    do {
      p = Eigen::Vector3d(unit(engine), unit(engine), unit(engine));
    } while (p.squaredNorm() > 1.0);
    points.row(i) << p.transpose(), 0.5 * (unit(engine) + 1.0);
  }
  return points;
}

// A smooth random field: centers in the unit ball x [0, 1], small random weights, a small
// polynomial part; it moves particles by a few tenths over t in [0, 1], like a correction field.
RbfField smooth_field(Eigen::Index centers, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> weight(-0.005, 0.005);
  RbfField field;
  field.centers = ball_points(engine, centers);
  field.weights.resize(centers, 3);
  for (Eigen::Index i = 0; i < field.weights.size(); ++i) field.weights.data()[i] = weight(engine);
  for (Eigen::Index i = 0; i < field.polynomial.size(); ++i)
    field.polynomial.data()[i] = weight(engine);
  return field;
}

// Double-precision operations of one term w_j phi(|y - c_j|) of the sum as kernel_math.h writes it,
// a fused multiply-add counted as 2 and the one division as 1: the squared distance 11 (4
// differences, 1 product, 3 multiply-adds), the logarithm's argument 1, the logarithm 29, phi's two
// products 2, the three weighted sums 6. nvcc's PTX of the term has these 35 instructions (6 add,
// 5 sub, 9 mul, 14 fma, 1 div); the division's own Newton steps are not counted.
constexpr double kFlopsPerTerm = 49.0;

cpu::KernelIsa isa_argument(std::int64_t value) { return static_cast<cpu::KernelIsa>(value); }

// "avx512 kernels, 2 threads"
std::string describe(const Device& device) {
  const DeviceInfo info = device.info();
  const std::string kernels = info.driver.substr(info.driver.find(", ") + 2);
  return kernels + ", " + std::to_string(info.compute_units) +
         (info.compute_units == 1 ? " thread" : " threads");
}

// Arguments: points, centers, instruction set (0 baseline, 1 avx2, 2 avx512), threads (0: all).
void BM_RbfEvaluation(benchmark::State& state) {
  const Eigen::Index points = state.range(0);
  const Eigen::Index centers = state.range(1);
  const cpu::KernelIsa isa = isa_argument(state.range(2));
  if (!cpu::is_supported(isa)) {
    state.SkipWithError("instruction set not supported here");
    return;
  }
  const std::unique_ptr<Device> device =
      cpu::make_cpu_device(static_cast<int>(state.range(3)), isa);
  std::mt19937_64 engine(1);
  const std::unique_ptr<DeviceField> field = device->upload_field(smooth_field(centers, 2));
  const Points4 queries = ball_points(engine, points);
  Eigen::MatrixX3d values(points, 3);
  for (auto _ : state) {
    device->evaluate_rbf(*field, queries, values);
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  state.counters["evaluations/s"] = benchmark::Counter(
      static_cast<double>(points * centers), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(describe(*device));
}
BENCHMARK(BM_RbfEvaluation)
    ->ArgNames({"points", "centers", "isa", "threads"})
    ->Args({65000, 2700, 2, 0})
    ->Args({65000, 2700, 2, 1})
    ->Args({65000, 2700, 1, 0})
    ->Args({65000, 2700, 0, 0})
    ->Args({65000, 128, 2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arguments: points, centers, instruction set; all threads, with the 15 polynomial columns.
void BM_RbfAssembly(benchmark::State& state) {
  const Eigen::Index points = state.range(0);
  const Eigen::Index centers = state.range(1);
  const cpu::KernelIsa isa = isa_argument(state.range(2));
  if (!cpu::is_supported(isa)) {
    state.SkipWithError("instruction set not supported here");
    return;
  }
  const std::unique_ptr<Device> device = cpu::make_cpu_device(0, isa);
  std::mt19937_64 engine(3);
  const Points4 point_set = ball_points(engine, points);
  const Points4 center_set = ball_points(engine, centers);
  // Touched once here, so that the first iteration does not time the page faults of a new block.
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(points, centers + kRbfPolynomialTerms);
  for (auto _ : state) {
    device->assemble_rbf_block(point_set, center_set, true, block);
    benchmark::DoNotOptimize(block.data());
    benchmark::ClobberMemory();
  }
  state.counters["evaluations/s"] = benchmark::Counter(
      static_cast<double>(points * centers), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(describe(*device));
}
BENCHMARK(BM_RbfAssembly)
    ->ArgNames({"points", "centers", "isa"})
    ->Args({65000, 128, 2})   // one center-selection round: new columns for every constraint
    ->Args({2700, 2700, 2})   // the whole RBF block of a finished fit
    ->Args({65000, 2700, 2})  // a 1.4 GB block: memory bound
    ->Args({2700, 2700, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// RK45 of `particles` particles through a smooth field of `centers` centers on `device`, with the
// default Rk45Options (rtol 1e-7, atol 1e-9, t from 0 to 1).
void run_rk45_batch(benchmark::State& state, Device& device, Eigen::Index particles,
                    Eigen::Index centers) {
  const std::unique_ptr<DeviceField> field = device.upload_field(smooth_field(centers, 4));
  std::mt19937_64 engine(5);
  const Eigen::MatrixX3d start = ball_points(engine, particles).leftCols<3>();
  Eigen::MatrixX3d positions = start.topRows(std::min<Eigen::Index>(particles, 64));
  device.integrate_rk45(*field, positions, Rk45Options());  // untimed first launch, a few particles
  positions = start;
  Rk45Summary summary;
  for (auto _ : state) {
    state.PauseTiming();
    positions = start;
    state.ResumeTiming();
    summary = summarize(device.integrate_rk45(*field, positions, Rk45Options()));
    benchmark::DoNotOptimize(positions.data());
  }
  const auto count = static_cast<double>(particles);
  const Eigen::VectorXd moved = (positions - start).rowwise().norm();
  state.counters["rhs/particle"] = static_cast<double>(summary.rhs_evaluations) / count;
  state.counters["steps/particle"] = static_cast<double>(summary.accepted_steps) / count;
  state.counters["rejected/particle"] = static_cast<double>(summary.rejected_steps) / count;
  state.counters["failures"] = static_cast<double>(summary.failures);
  state.counters["mean_moved"] = moved.mean();
  state.counters["max_moved"] = moved.maxCoeff();
  state.counters["evaluations/s"] = benchmark::Counter(
      static_cast<double>(summary.rhs_evaluations) * static_cast<double>(centers),
      benchmark::Counter::kIsIterationInvariantRate);
}

// Arguments: particles, centers; the CPU backend with every hardware thread.
void BM_Rk45Batch(benchmark::State& state) {
  const std::unique_ptr<Device> device = make_cpu_device();
  run_rk45_batch(state, *device, state.range(0), state.range(1));
  state.SetLabel(describe(*device));
}
BENCHMARK(BM_Rk45Batch)
    ->ArgNames({"particles", "centers"})
    ->Args({5000, 2700})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// ---------------------------------------------------------------------------------------------
// Choosing a device

// What `posekit correct` pays before its first kernel: the registry's choice for "auto" and the
// device's construction and destruction. The process has already probed every backend while
// registering the BM_Backend* benchmarks, so drivers' libraries are loaded: this is the warm cost,
// which a fresh process exceeds by the libraries' first initialization.
void BM_CreateAutoDevice(benchmark::State& state) {
  std::string chosen;
  for (auto _ : state) {
    const std::unique_ptr<Device> device = create_device("auto");
    benchmark::DoNotOptimize(device.get());
    if (chosen.empty()) chosen = device->info().backend;
  }
  state.SetLabel(chosen);
}
BENCHMARK(BM_CreateAutoDevice)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same for the named cpu backend: the floor that "auto" can reach on a machine without a GPU.
void BM_CreateCpuDevice(benchmark::State& state) {
  for (auto _ : state) {
    const std::unique_ptr<Device> device = create_device("cpu");
    benchmark::DoNotOptimize(device.get());
  }
}
BENCHMARK(BM_CreateCpuDevice)->Unit(benchmark::kMillisecond)->UseRealTime();

// ---------------------------------------------------------------------------------------------
// Every available backend

// One device per backend for the whole run; nullptr (with the reason printed) when it cannot be
// created.
Device* backend_device(const std::string& backend) {
  static std::map<std::string, std::unique_ptr<Device>> devices;
  const auto found = devices.find(backend);
  if (found != devices.end()) return found->second.get();
  std::unique_ptr<Device>& device = devices[backend];
  try {
    device = create_device(backend);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "posekit_device_bench: %s skipped: %s\n", backend.c_str(), error.what());
  }
  return device.get();
}

std::string backend_label(const Device& device) {
  const DeviceInfo info = device.info();
  return info.backend + ": " + info.name;
}

void BM_BackendRbfEvaluation(benchmark::State& state, const std::string& backend) {
  Device* device = backend_device(backend);
  if (device == nullptr) {
    state.SkipWithError("backend unavailable here");
    return;
  }
  const Eigen::Index points = state.range(0);
  const Eigen::Index centers = state.range(1);
  std::mt19937_64 engine(1);
  const std::unique_ptr<DeviceField> field = device->upload_field(smooth_field(centers, 2));
  const Points4 queries = ball_points(engine, points);
  Eigen::MatrixX3d values(points, 3);
  // Once untimed: a runtime may finish compiling a kernel on its first launch.
  device->evaluate_rbf(*field, queries, values);
  for (auto _ : state) {
    device->evaluate_rbf(*field, queries, values);
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  state.counters["evaluations/s"] = benchmark::Counter(
      static_cast<double>(points * centers), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["fp64_flop/s"] =
      benchmark::Counter(kFlopsPerTerm * static_cast<double>(points * centers),
                         benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(backend_label(*device));
}

void BM_BackendRbfAssembly(benchmark::State& state, const std::string& backend) {
  Device* device = backend_device(backend);
  if (device == nullptr) {
    state.SkipWithError("backend unavailable here");
    return;
  }
  const Eigen::Index points = state.range(0);
  const Eigen::Index centers = state.range(1);
  std::mt19937_64 engine(3);
  const Points4 point_set = ball_points(engine, points);
  const Points4 center_set = ball_points(engine, centers);
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(points, centers + kRbfPolynomialTerms);
  device->assemble_rbf_block(point_set, center_set, true, block);  // untimed first launch
  for (auto _ : state) {
    device->assemble_rbf_block(point_set, center_set, true, block);
    benchmark::DoNotOptimize(block.data());
    benchmark::ClobberMemory();
  }
  state.counters["evaluations/s"] = benchmark::Counter(
      static_cast<double>(points * centers), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(backend_label(*device));
}

void BM_BackendRk45Batch(benchmark::State& state, const std::string& backend) {
  Device* device = backend_device(backend);
  if (device == nullptr) {
    state.SkipWithError("backend unavailable here");
    return;
  }
  run_rk45_batch(state, *device, state.range(0), state.range(1));
  state.SetLabel(backend_label(*device));
}

// The BM_Backend* benchmarks, once per available backend, at the sizes of the CPU ones above.
void register_backend_benchmarks() {
  for (const BackendStatus& status : list_backends()) {
    if (status.state != BackendState::available) continue;
    const std::string& name = status.name;
    benchmark::RegisterBenchmark(("BM_BackendRbfEvaluation/" + name).c_str(),
                                 BM_BackendRbfEvaluation, name)
        ->ArgNames({"points", "centers"})
        ->Args({65000, 2700})
        ->Args({65000, 128})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("BM_BackendRbfAssembly/" + name).c_str(), BM_BackendRbfAssembly,
                                 name)
        ->ArgNames({"points", "centers"})
        ->Args({65000, 128})
        ->Args({2700, 2700})
        ->Args({65000, 2700})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("BM_BackendRk45Batch/" + name).c_str(), BM_BackendRk45Batch,
                                 name)
        ->ArgNames({"particles", "centers"})
        ->Args({5000, 2700})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
}

}  // namespace
}  // namespace posekit

// Benchmark's own main, after the backends' benchmarks are registered (they depend on what the
// registry finds at run time).
int main(int argc, char** argv) {
  posekit::register_backend_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
