// End-to-end pose correction on the CPU device, stage by stage: the generated demo arm (its 135
// degree bend against the rest pose) and, when ../shared/data is present, lion-reference -> lion-01.
// Counters are the seconds of each stage of the last iteration, the centers and the new
// intersecting faces of the result.
#include <posekit/correct.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/mesh_io.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>
#include <iostream>
#include <memory>

namespace posekit {
namespace {

void correct_and_count(benchmark::State& state, const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& target,
                       const Eigen::MatrixX3i& faces) {
  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionReport report;
  for (auto _ : state) {
    benchmark::DoNotOptimize(correct_pose(reference, target, faces, *device, CorrectionOptions{}, &report));
  }
  state.counters["key_frames_s"] = report.seconds.key_frames;
  state.counters["classification_s"] = report.seconds.classification;
  state.counters["constraints_s"] = report.seconds.constraints;
  state.counters["fitting_s"] = report.seconds.fitting;
  state.counters["integration_s"] = report.seconds.integration;
  state.counters["drift_s"] = report.seconds.drift_compensation;
  state.counters["verification_s"] = report.seconds.verification;
  state.counters["centers"] = report.fit.centers;
  state.counters["new_faces"] = report.new_intersecting_faces;
}

void BM_CorrectDemoArm(benchmark::State& state) {
  DemoArmOptions options;
  options.bend_angles_degrees = {135.0};
  const PoseSet arm = make_demo_arm(options);
  correct_and_count(state, arm.pose(0), arm.pose(1), arm.faces());
}
BENCHMARK(BM_CorrectDemoArm)->Unit(benchmark::kSecond)->Iterations(1);

void BM_CorrectLion01(benchmark::State& state) {
  const std::filesystem::path folder = std::filesystem::path(POSEKIT_BENCH_DATA_DIR) / "lion-poses";
  if (!std::filesystem::exists(folder / "lion-01.obj")) {
    state.SkipWithError("shared pose data not found: lion-poses/lion-01.obj");
    return;
  }
  const Mesh reference = read_mesh(folder / "lion-reference.obj");
  const Mesh target = read_mesh(folder / "lion-01.obj");
  correct_and_count(state, reference.vertices, target.vertices, reference.faces);
}
BENCHMARK(BM_CorrectLion01)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace posekit

BENCHMARK_MAIN();
