// Pose correction end to end on the CPU device, stage by stage.
//  - BM_CorrectArm: the generated arm's 135 degree bend at 4k, 16k, 64k and 256k vertices, with the
//    regions of interest and with the whole mesh: finer (the same arm, more rings) and longer (the
//    same joint at the same resolution, more arm away from it). How the time grows with the vertex
//    count is the point: it should follow the joint, not the mesh.
//  - BM_CorrectSharedPose: every lion, cat and horse target against its reference, elephant-02 ...
//    elephant-10 against elephant-01 and crane frames against crane-0014, when ../shared/data is
//    present (skipped with a message otherwise).
//  - BM_SeparateContacts: the separation of cat-07's own contacts alone.
//  - BM_CorrectCraneSequence: crane-0000 ... crane-0174 as one animation against crane-0014
//    (correct_sequence), with its counts and coherence figures; carry=0 corrects every frame alone.
// Counters: the seconds of the field's steps and of each repair stage that ran, the centers, the
// region's vertices and the new intersecting faces of the result.
#include <posekit/correct.hpp>
#include <posekit/correct_sequence.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include "correct/contact_separation.hpp"

#include "crane_frames.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>

#include <filesystem>
#include <memory>
#include <string>

namespace posekit {
namespace {

void correct_and_count(benchmark::State& state, const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& target,
                       const Eigen::MatrixX3i& faces, const CorrectionOptions& options = {}) {
  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionReport report;
  for (auto _ : state) {
    benchmark::DoNotOptimize(correct_pose(reference, target, faces, *device, options, &report));
  }
  state.counters["vertices"] = static_cast<double>(reference.rows());
  state.counters["region_vertices"] = report.field.region_vertices;
  state.counters["key_frames_s"] = report.field.seconds.key_frames;
  state.counters["classification_s"] = report.field.seconds.classification;
  state.counters["fitting_s"] = report.field.seconds.fitting;
  state.counters["integration_s"] = report.field.seconds.integration + report.field.seconds.drift_compensation;
  state.counters["reproduction_s"] = report.field.seconds.reproduction;
  for (const StageReport& stage : report.stages) {
    if (stage.ran) state.counters[stage.name + "_s"] += stage.seconds;
  }
  state.counters["centers"] = report.field.centers();
  state.counters["new_faces"] = report.result.new_intersecting_faces;
  state.counters["median_per_diagonal"] = report.result.median_distance_to_target / report.result.bounding_box_diagonal;
  state.counters["stretched"] = report.result.stretched_faces;
}

// The arm of about `kvertices` thousand vertices (4, 16, 64 or 256): finer (more vertices around
// and along the same arm) or longer (the 4k arm's resolution and joint, as many vertices, the arm
// longer away from the joint).
DemoArmOptions arm_of(int kvertices, bool longer) {
  DemoArmOptions arm;
  arm.bend_angles_degrees = {135.0};
  int factor = 1;
  while (factor * factor < kvertices / 4) ++factor;
  DemoArmOptions finer = arm;
  finer.ring_segments *= factor;
  if (!longer) return finer;
  // The finer arm's vertex count in rings of the 4k arm's segments: the caps keep theirs.
  const auto target = static_cast<double>(make_demo_arm(finer).pose(0).rows());
  const double spacing = 2.0 * M_PI * arm.radius / arm.ring_segments;
  arm.cylinder_length = (target / arm.ring_segments - 2.0 * (arm.ring_segments / 4) + 1.0) * spacing;
  return arm;
}

// range(0): thousands of vertices; range(1): 1 for the longer arm; range(2): 1 for the whole mesh.
void BM_CorrectArm(benchmark::State& state) {
  const PoseSet poses = make_demo_arm(arm_of(static_cast<int>(state.range(0)), state.range(1) == 1));
  CorrectionOptions options;
  options.whole_mesh = state.range(2) == 1;
  correct_and_count(state, poses.pose(0), poses.pose(1), poses.faces(), options);
}
BENCHMARK(BM_CorrectArm)
    ->ArgNames({"kvertices", "longer", "whole_mesh"})
    ->ArgsProduct({{4, 16, 64, 256}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

std::filesystem::path shared_data() { return POSEKIT_BENCH_DATA_DIR; }

void BM_CorrectSharedPose(benchmark::State& state, const std::string& reference_file, const std::string& target_file) {
  const std::filesystem::path reference_path = shared_data() / reference_file;
  const std::filesystem::path target_path = shared_data() / target_file;
  if (!std::filesystem::exists(reference_path) || !std::filesystem::exists(target_path)) {
    state.SkipWithError(("shared pose data not found: " + target_file).c_str());
    return;
  }
  const Mesh reference = read_mesh(reference_path);
  const Mesh target = read_mesh(target_path);
  correct_and_count(state, reference.vertices, target.vertices, reference.faces);
}

// Registers one benchmark per pose of the set: lion, cat and horse targets, elephant-02 to
// elephant-10, and crane frames 21-44 and 85-95.
const bool registered = [] {
  const auto add = [](const std::string& name, const std::string& reference, const std::string& target) {
    benchmark::RegisterBenchmark(("BM_CorrectSharedPose/" + name).c_str(), BM_CorrectSharedPose, reference, target)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
  };
  const auto two_digits = [](int i) { return (i < 10 ? "0" : "") + std::to_string(i); };
  for (const char* animal : {"lion", "cat"}) {
    for (int i = 1; i <= 9; ++i) {
      const std::string folder = std::string(animal) + "-poses/";
      add(std::string(animal) + "-" + two_digits(i), folder + animal + "-reference.obj",
          folder + animal + "-" + two_digits(i) + ".obj");
    }
  }
  for (int i = 1; i <= 9; ++i) add("horse-" + two_digits(i), "horse-poses/horse-10.obj", "horse-poses/horse-" + two_digits(i) + ".obj");
  for (int i = 2; i <= 10; ++i) {
    add("elephant-" + two_digits(i), "elephant-poses/elephant-01.obj", "elephant-poses/elephant-" + two_digits(i) + ".obj");
  }
  for (int frame = 21; frame <= 95; ++frame) {
    if (frame > 44 && frame < 85) continue;
    const std::string name = "crane-00" + two_digits(frame);
    add(name, "crane-sequence/crane-0014.obj", "crane-sequence/" + name + ".obj");
  }
  return true;
}();

// range(0): 1 to carry a frame's correction to the next, 0 to correct every frame alone.
void BM_CorrectCraneSequence(benchmark::State& state) {
  std::vector<std::string> names;
  std::string missing;
  const std::vector<Eigen::MatrixX3d> frames = read_crane_frames(shared_data(), names, missing);
  if (frames.empty()) {
    state.SkipWithError(("shared pose data not found: " + missing).c_str());
    return;
  }
  const Mesh reference = read_mesh(shared_data() / "crane-sequence/crane-0014.obj");
  const std::unique_ptr<Device> device = make_cpu_device();
  SequenceCorrectionOptions options;
  options.carry_corrections = state.range(0) == 1;
  SequenceReport report;
  for (auto _ : state) {
    benchmark::DoNotOptimize(correct_sequence(reference.vertices, frames, reference.faces, *device, options, &report));
  }
  state.counters["frames"] = report.frames;
  state.counters["corrected"] = report.corrected_frames;
  state.counters["carried"] = report.carried_frames;
  state.counters["with_new_faces"] = report.frames_with_new_faces;
  state.counters["correction_s"] = report.correction_seconds;
  state.counters["coherence_s"] = report.coherence_seconds;
  state.counters["accel_p99_ratio"] = report.coherence.acceleration_p99_ratio;
  state.counters["accel_max_ratio"] = report.coherence.acceleration_max_ratio;
  state.counters["offset_change"] = report.coherence.largest_offset_change;
  state.counters["offset_change_alone"] = report.coherence.largest_offset_change_alone;
}
BENCHMARK(BM_CorrectCraneSequence)->ArgName("carry")->Arg(1)->Arg(0)->Unit(benchmark::kSecond)->Iterations(1);

// The stage that frees the most entangled cat target, on its own.
void BM_SeparateContacts(benchmark::State& state) {
  const std::filesystem::path folder = shared_data() / "cat-poses";
  if (!std::filesystem::exists(folder / "cat-07.obj")) {
    state.SkipWithError("shared pose data not found: cat-poses/cat-07.obj");
    return;
  }
  const Mesh reference = read_mesh(folder / "cat-reference.obj");
  const Mesh target = read_mesh(folder / "cat-07.obj");
  const std::unique_ptr<Device> device = make_cpu_device();
  const CorrectionOptions options;
  const detail::CorrectionContext context = detail::make_context(
      reference.vertices, target.vertices, reference.faces, *device, options, detail::CorrectionScope::whole_pose, {});
  int rounds = 0;
  int before = 0;
  int after = 0;
  for (auto _ : state) {
    const detail::SeparationOutcome separation = detail::separate_contacts(
        context, detail::Candidate(context.target, context.faces, context.reference_intersecting, context.target_pairs));
    rounds = separation.rounds;
    before = separation.new_faces_before;
    after = separation.best.new_face_count();
    benchmark::DoNotOptimize(separation.best.pose().data());
  }
  state.counters["rounds"] = rounds;
  state.counters["new_faces_before"] = before;
  state.counters["new_faces"] = after;
}
BENCHMARK(BM_SeparateContacts)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace posekit

BENCHMARK_MAIN();
