// Interpolation in the mixed shape space (MixIT) against its two baselines on the shared poses
// (../shared/data): horse-10 -> horse-01, cat-reference -> cat-01, lion-reference -> lion-03 and
// elephant-01 -> elephant-02 at weights 0.25, 0.5 and 0.75, and four horse poses with equal weights.
// "precompute/..." times building an interpolator (segmentation, registration, factorizations);
// "interpolate/..." times one weight vector after that. Counters: the result's errors against the
// linearly interpolated edge lengths and dihedral angles (percent, degrees), its collapsed, folded and
// flipped faces, the share of joint faces, and the stage times (ms) of the last call. The whole-mesh
// edge method on the elephant takes minutes per call and runs once; everything else repeats as
// --benchmark_repetitions says, with the minimum reported beside mean and median.
//
//   posekit_interpolate_bench --benchmark_repetitions=5 --benchmark_format=json > interpolate.json
//   python3 tools/bench/interpolation_table.py interpolate.json
#include <posekit/interpolate.hpp>
#include <posekit/mesh_io.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

namespace posekit {
namespace {

struct Case {
  std::string name;
  std::vector<std::string> files;  // relative to the shared data folder
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all{
      {"horse", {"horse-poses/horse-10.obj", "horse-poses/horse-01.obj"}},
      {"cat", {"cat-poses/cat-reference.obj", "cat-poses/cat-01.obj"}},
      {"lion", {"lion-poses/lion-reference.obj", "lion-poses/lion-03.obj"}},
      {"elephant", {"elephant-poses/elephant-01.obj", "elephant-poses/elephant-02.obj"}},
      {"horse-4", {"horse-poses/horse-10.obj", "horse-poses/horse-01.obj", "horse-poses/horse-03.obj",
                   "horse-poses/horse-05.obj"}},
  };
  return all;
}

// Pose sets are read once; interpolators are built once per case and method, outside the timing.
const PoseSet* poses_of(const Case& c) {
  static std::map<std::string, std::unique_ptr<PoseSet>> cache;
  auto found = cache.find(c.name);
  if (found != cache.end()) return found->second.get();
  std::vector<std::filesystem::path> files;
  for (const std::string& file : c.files) {
    const std::filesystem::path path = std::filesystem::path(POSEKIT_BENCH_DATA_DIR) / file;
    if (!std::filesystem::exists(path)) return nullptr;
    files.push_back(path);
  }
  return (cache[c.name] = std::make_unique<PoseSet>(read_pose_set(files))).get();
}

PoseInterpolator& interpolator_of(const Case& c, InterpolationMethod method, const PoseSet& poses) {
  static std::map<std::string, std::unique_ptr<PoseInterpolator>> cache;
  const std::string key = c.name + "/" + to_string(method);
  auto found = cache.find(key);
  if (found != cache.end()) return *found->second;
  InterpolationOptions options;
  options.method = method;
  return *(cache[key] = std::make_unique<PoseInterpolator>(poses, options));
}

void BM_Precompute(benchmark::State& state, const Case& c, InterpolationMethod method) {
  const PoseSet* poses = poses_of(c);
  if (poses == nullptr) {
    state.SkipWithError("shared pose data not found");
    return;
  }
  InterpolationOptions options;
  options.method = method;
  PrecomputationTimes seconds;
  InterpolationLayout layout;
  for (auto _ : state) {
    PoseInterpolator interpolator(*poses, options);
    seconds = interpolator.precomputation_seconds();
    layout = interpolator.layout();
  }
  state.counters["segmentation_ms"] = 1000.0 * seconds.segmentation;
  state.counters["registration_ms"] = 1000.0 * seconds.registration;
  state.counters["factorization_ms"] = 1000.0 * seconds.factorization;
  state.counters["joint_faces_pct"] = 100.0 * layout.joint_faces / static_cast<double>(poses->faces().rows());
  state.counters["parts"] = layout.parts;
  state.counters["joints"] = layout.joints;
}

void BM_Interpolate(benchmark::State& state, const Case& c, InterpolationMethod method, Eigen::VectorXd weights) {
  const PoseSet* poses = poses_of(c);
  if (poses == nullptr) {
    state.SkipWithError("shared pose data not found");
    return;
  }
  PoseInterpolator& interpolator = interpolator_of(c, method, *poses);
  Eigen::MatrixX3d result;
  InterpolationStepReport report;
  for (auto _ : state) {
    result = interpolator.interpolate(weights, &report);
    benchmark::DoNotOptimize(result.data());
  }
  const InterpolationError error = interpolator.error(result, weights);
  state.counters["len_p99_pct"] = 100.0 * error.edge_length.p99;
  state.counters["len_p999_pct"] = 100.0 * error.edge_length.p999;
  state.counters["len_max_pct"] = 100.0 * error.edge_length.max;
  state.counters["dih_p99_deg"] = error.dihedral_degrees.p99;
  state.counters["dih_p999_deg"] = error.dihedral_degrees.p999;
  state.counters["dih_max_deg"] = error.dihedral_degrees.max;
  state.counters["collapsed"] = error.collapsed_faces;
  state.counters["folded"] = error.folded_edges;
  state.counters["flipped"] = error.flipped_faces;
  state.counters["joint_faces_pct"] =
      100.0 * interpolator.layout().joint_faces / static_cast<double>(poses->faces().rows());
  const InterpolationTimes& s = report.seconds;
  state.counters["joints_ms"] = 1000.0 * s.joints;
  state.counters["refinement_ms"] = 1000.0 * s.refinement;
  state.counters["projection_ms"] = 1000.0 * s.projection;
}

double minimum(const std::vector<double>& values) { return *std::min_element(values.begin(), values.end()); }

void register_all() {
  const InterpolationMethod methods[] = {InterpolationMethod::mixit, InterpolationMethod::edge, InterpolationMethod::vertex};
  for (const Case& c : cases()) {
    for (const InterpolationMethod method : methods) {
      const bool slow = method == InterpolationMethod::edge;
      benchmark::internal::Benchmark* precompute = benchmark::RegisterBenchmark(
          ("precompute/" + c.name + "/" + to_string(method)).c_str(),
          [&c, method](benchmark::State& state) { BM_Precompute(state, c, method); });
      precompute->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->ComputeStatistics("min", minimum);
      std::vector<std::pair<std::string, Eigen::VectorXd>> weights;
      if (c.files.size() == 2) {
        for (const double t : {0.25, 0.5, 0.75}) {
          std::ostringstream name;
          name << std::fixed << std::setprecision(2) << t;
          weights.emplace_back(name.str(), two_pose_weights(t));
        }
      } else {
        const auto count = static_cast<Eigen::Index>(c.files.size());
        weights.emplace_back("equal", Eigen::VectorXd::Constant(count, 1.0 / static_cast<double>(count)));
      }
      for (const auto& [label, w] : weights) {
        benchmark::internal::Benchmark* run = benchmark::RegisterBenchmark(
            ("interpolate/" + c.name + "/" + to_string(method) + "/" + label).c_str(),
            [&c, method, w = w](benchmark::State& state) { BM_Interpolate(state, c, method, w); });
        run->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", minimum);
        if (slow) run->Iterations(1);
        if (slow && c.name == "elephant") {
          run->Repetitions(1);
          precompute->Repetitions(1);
        }
      }
    }
  }
}

}  // namespace
}  // namespace posekit

int main(int argc, char** argv) {
  posekit::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
