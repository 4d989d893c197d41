// HTML reports: building the page of a correction (lion-01) and of a whole captured sequence (the
// crane's 175 frames), from the intersection tests of every pose shown to the page's bytes.
#include "crane_frames.hpp"
#include "html_page.hpp"
#include "job_pages.hpp"

#include <posekit/correct.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>

namespace posekit {
namespace {

std::filesystem::path shared_data() { return POSEKIT_BENCH_DATA_DIR; }

void BM_CorrectionPage(benchmark::State& state) {
  const std::filesystem::path reference_file = shared_data() / "lion-poses/lion-reference.obj";
  const std::filesystem::path target_file = shared_data() / "lion-poses/lion-01.obj";
  if (!std::filesystem::exists(reference_file) || !std::filesystem::exists(target_file)) {
    state.SkipWithError("shared pose data not found: lion-poses");
    return;
  }
  const Mesh reference = read_mesh(reference_file);
  const Mesh target = read_mesh(target_file);
  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionReport report;
  const Eigen::MatrixX3d result =
      correct_pose(reference.vertices, target.vertices, reference.faces, *device, {}, &report);
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string page = report::html_page(
        report::correction_page(reference.vertices, target.vertices, result, reference.faces, report, "bench"));
    bytes = page.size();
    benchmark::DoNotOptimize(page.data());
  }
  state.counters["megabytes"] = static_cast<double>(bytes) / (1024.0 * 1024.0);
}
BENCHMARK(BM_CorrectionPage)->Unit(benchmark::kMillisecond);

// Every frame's result differs from its target (one vertex moved), so that every pose is tested and
// stored: the largest page a sequence of this length gives.
void BM_SequencePage(benchmark::State& state) {
  std::vector<std::string> names;
  std::string missing;
  const std::vector<Eigen::MatrixX3d> frames = read_crane_frames(shared_data(), names, missing);
  if (frames.empty()) {
    state.SkipWithError(("shared pose data not found: " + missing).c_str());
    return;
  }
  const Mesh reference = read_mesh(shared_data() / "crane-sequence/crane-0014.obj");
  SequenceReport report;
  report.frames = static_cast<int>(frames.size());
  report.bounding_box_diagonal = bounding_box_diagonal(reference.vertices);
  std::vector<Eigen::MatrixX3d> results = frames;
  for (Eigen::MatrixX3d& result : results) result(0, 0) += 1e-3 * report.bounding_box_diagonal;
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string page = report::html_page(
        report::sequence_page(reference.vertices, frames, results, reference.faces, names, report, "bench"));
    bytes = page.size();
    benchmark::DoNotOptimize(page.data());
  }
  state.counters["megabytes"] = static_cast<double>(bytes) / (1024.0 * 1024.0);
}
BENCHMARK(BM_SequencePage)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace posekit

BENCHMARK_MAIN();
