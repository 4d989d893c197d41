// End-to-end pose correction on the CPU device, stage by stage: the generated demo arm (its 135
// degree bend against the rest pose) and, when ../shared/data is present, lion-reference -> lion-01
// (integration leaves little to mend), lion-08 (the rollback, local correction and relaxation
// work) and lion-04 (the local correction of the target itself); and the separation of cat-07's own
// contacts alone. Counters are the seconds of each stage of the last iteration, the centers and the
// new intersecting faces of the result.
#include <posekit/correct.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include "correct/contact_separation.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

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
  state.counters["reproduction_s"] = report.seconds.reproduction;
  state.counters["verification_s"] = report.seconds.verification;
  state.counters["rollback_s"] = report.seconds.rollback;
  state.counters["local_s"] = report.seconds.local_correction;
  state.counters["relaxation_s"] = report.seconds.relaxation;
  state.counters["separation_s"] = report.seconds.separation;
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

void BM_CorrectSharedLionPose(benchmark::State& state, const std::string& pose) {
  const std::filesystem::path folder = std::filesystem::path(POSEKIT_BENCH_DATA_DIR) / "lion-poses";
  if (!std::filesystem::exists(folder / (pose + ".obj"))) {
    state.SkipWithError(("shared pose data not found: lion-poses/" + pose + ".obj").c_str());
    return;
  }
  const Mesh reference = read_mesh(folder / "lion-reference.obj");
  const Mesh target = read_mesh(folder / (pose + ".obj"));
  correct_and_count(state, reference.vertices, target.vertices, reference.faces);
}
BENCHMARK_CAPTURE(BM_CorrectSharedLionPose, lion_01, std::string("lion-01"))->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_CorrectSharedLionPose, lion_08, std::string("lion-08"))->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_CorrectSharedLionPose, lion_04, std::string("lion-04"))->Unit(benchmark::kSecond)->Iterations(1);

// The stage that frees cat-07 (1,324 new intersecting faces in the target), on its own.
void BM_SeparateContacts(benchmark::State& state) {
  const std::filesystem::path folder = std::filesystem::path(POSEKIT_BENCH_DATA_DIR) / "cat-poses";
  if (!std::filesystem::exists(folder / "cat-07.obj")) {
    state.SkipWithError("shared pose data not found: cat-poses/cat-07.obj");
    return;
  }
  const Mesh reference = read_mesh(folder / "cat-reference.obj");
  const Mesh target = read_mesh(folder / "cat-07.obj");
  const std::vector<int> reference_faces = self_intersecting_faces(reference.vertices, reference.faces);
  detail::SeparationResult separation;
  for (auto _ : state) {
    separation = detail::separate_contacts(target.vertices, reference.vertices, reference.faces, reference_faces);
    benchmark::DoNotOptimize(separation.pose.data());
  }
  state.counters["rounds"] = separation.iterations;
  state.counters["new_faces_before"] = separation.new_faces_before;
  state.counters["new_faces"] = separation.new_faces_after;
}
BENCHMARK(BM_SeparateContacts)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace posekit

BENCHMARK_MAIN();
