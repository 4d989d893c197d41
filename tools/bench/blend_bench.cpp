// Example-based deformation after precomputation: one deformation from 10 point constraints (the
// interactive case) and its final vertex evaluation, one constraint replaced by a rank-one update against a full refactorization,
// one interpolated frame. On the horse (horse-01.. as examples, horse-10's vertices as targets) with
// 4 and 9 examples when ../shared/data is present, and on the generated demo arm. The same deformation
// with the skeleton dictionary and its vertex evaluation, and the skinning decomposition behind it (the 10 horse poses).
#include <posekit/blended_deformation.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

namespace posekit {
namespace {

struct Case {
  PoseSet examples;
  Eigen::MatrixX3d target;
  std::unique_ptr<BlendedDeformer> deformer;
  std::vector<LinearConstraint> constraints;
  Eigen::MatrixX3d targets;
};

// The machine may be shared: the minimum over repetitions is the number to quote.
double minimum(const std::vector<double>& values) { return *std::min_element(values.begin(), values.end()); }


void constrain(Case& c, int count) {
  const std::vector<int> points = farthest_point_samples(c.target, count);
  c.constraints.clear();
  c.targets.resize(count, 3);
  for (int r = 0; r < count; ++r) {
    c.constraints.push_back(LinearConstraint::vertex(points[static_cast<size_t>(r)]));
    c.targets.row(r) = c.target.row(points[static_cast<size_t>(r)]);
  }
  c.deformer->set_constraints(c.constraints);
}

// Built once per example count and kept: the precomputation is not what is measured.
std::vector<std::filesystem::path> horse_files(int count) {
  const std::filesystem::path folder = std::filesystem::path(POSEKIT_BENCH_DATA_DIR) / "horse-poses";
  std::vector<std::filesystem::path> files;
  for (int k = 1; k <= count; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "horse-%02d.obj", k);
    files.push_back(folder / name);
  }
  return files;
}

Case* horse(int examples, DictionaryChoice dictionary = DictionaryChoice::lbo) {
  static std::map<std::pair<int, DictionaryChoice>, std::unique_ptr<Case>> cache;
  auto& slot = cache[{examples, dictionary}];
  if (slot) return slot.get();
  const std::filesystem::path folder = std::filesystem::path(POSEKIT_BENCH_DATA_DIR) / "horse-poses";
  if (!std::filesystem::exists(folder / "horse-10.obj")) return nullptr;
  slot = std::make_unique<Case>();
  slot->examples = read_pose_set(horse_files(examples));
  slot->target = read_mesh(folder / "horse-10.obj").vertices;
  BlendOptions options;
  options.dictionary = dictionary;
  slot->deformer = std::make_unique<BlendedDeformer>(slot->examples, options);
  constrain(*slot, 10);
  return slot.get();
}

Case* arm() {
  static std::unique_ptr<Case> c;
  if (c) return c.get();
  c = std::make_unique<Case>();
  DemoArmOptions options;
  options.bend_angles_degrees = {45.0, 90.0, 135.0};
  c->examples = make_demo_arm(options);
  options.bend_angles_degrees = {67.5};
  c->target = make_demo_arm(options).pose(1);
  c->deformer = std::make_unique<BlendedDeformer>(c->examples);
  constrain(*c, 10);
  return c.get();
}

void report_sizes(benchmark::State& state, const Case& c) {
  const BlendSetupReport& r = c.deformer->setup_report();
  state.counters["vertices"] = r.vertices;
  state.counters["examples"] = r.examples;
  state.counters["atoms"] = r.atoms;
  state.counters["clusters"] = r.clusters;
  state.counters["bones"] = r.bones;
  state.counters["setup_s"] = r.seconds.total;
}

void deform(benchmark::State& state, Case* c) {
  if (c == nullptr) {
    state.SkipWithError("shared pose data not found: horse-poses");
    return;
  }
  BlendResult result;
  for (auto _ : state) {
    result = c->deformer->deform(c->targets);
    benchmark::DoNotOptimize(result.vertices.data());
  }
  report_sizes(state, *c);
  state.counters["iterations"] = static_cast<double>(result.iterations.size());
}

void BM_DeformHorse(benchmark::State& state) { deform(state, horse(static_cast<int>(state.range(0)))); }
BENCHMARK(BM_DeformHorse)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_DeformHorseSkeleton(benchmark::State& state) {
  deform(state, horse(static_cast<int>(state.range(0)), DictionaryChoice::skeleton));
}
BENCHMARK(BM_DeformHorseSkeleton)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

// The skinning decomposition of the 10 horse poses (automatic bone count).
void BM_SkinningDecompositionHorse(benchmark::State& state) {
  const std::vector<std::filesystem::path> files = horse_files(10);
  if (!std::filesystem::exists(files.back())) {
    state.SkipWithError("shared pose data not found: horse-poses");
    return;
  }
  const PoseSet examples = read_pose_set(files);
  SkinningDecomposition result;
  for (auto _ : state) {
    result = decompose_skinning(examples);
    benchmark::DoNotOptimize(result.weights.data());
  }
  state.counters["bones"] = result.bone_count();
  state.counters["rms_error_percent"] = 100 * result.rms_error;
}
BENCHMARK(BM_SkinningDecompositionHorse)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_DeformArm(benchmark::State& state) { deform(state, arm()); }
BENCHMARK(BM_DeformArm)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

// The last part of every deformation: the vertices D T of the result, in either dictionary.
void vertices(benchmark::State& state, Case* c) {
  if (c == nullptr) {
    state.SkipWithError("shared pose data not found: horse-poses");
    return;
  }
  const BlendResult result = c->deformer->deform(c->targets);
  for (auto _ : state) benchmark::DoNotOptimize(c->deformer->vertices(result.transformations).data());
  report_sizes(state, *c);
}

void BM_VerticesHorse(benchmark::State& state) { vertices(state, horse(static_cast<int>(state.range(0)))); }
BENCHMARK(BM_VerticesHorse)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_VerticesHorseSkeleton(benchmark::State& state) {
  vertices(state, horse(static_cast<int>(state.range(0)), DictionaryChoice::skeleton));
}
BENCHMARK(BM_VerticesHorseSkeleton)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

// Moving one constraint to another vertex: a rank-one update and a downdate of both factors ...
void BM_ReplaceConstraintHorse(benchmark::State& state) {
  Case* c = horse(static_cast<int>(state.range(0)));
  if (c == nullptr) {
    state.SkipWithError("shared pose data not found: horse-poses");
    return;
  }
  int flip = 0;
  for (auto _ : state) {
    c->deformer->replace_constraint(0, LinearConstraint::vertex(flip++ % 2 == 0 ? 17 : c->constraints[0].vertices[0]));
  }
  c->deformer->set_constraints(c->constraints);
  report_sizes(state, *c);
}
BENCHMARK(BM_ReplaceConstraintHorse)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

// ... against factorizing both matrices anew.
void BM_SetConstraintsHorse(benchmark::State& state) {
  Case* c = horse(static_cast<int>(state.range(0)));
  if (c == nullptr) {
    state.SkipWithError("shared pose data not found: horse-poses");
    return;
  }
  for (auto _ : state) c->deformer->set_constraints(c->constraints);
  report_sizes(state, *c);
}
BENCHMARK(BM_SetConstraintsHorse)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_InterpolateHorse(benchmark::State& state) {
  Case* c = horse(static_cast<int>(state.range(0)));
  if (c == nullptr) {
    state.SkipWithError("shared pose data not found: horse-poses");
    return;
  }
  const BlendResult a = c->deformer->deform(c->targets);
  const BlendResult b = c->deformer->deform(c->targets * 1.1);
  for (auto _ : state) benchmark::DoNotOptimize(c->deformer->interpolate(a, b, 0.5).data());
  report_sizes(state, *c);
}
BENCHMARK(BM_InterpolateHorse)->Arg(4)->Arg(9)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

}  // namespace
}  // namespace posekit

BENCHMARK_MAIN();
