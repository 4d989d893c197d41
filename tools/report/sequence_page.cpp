#include "job_pages.hpp"
#include "pose_highlights.hpp"

#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>

namespace posekit::report {

ReportDocument sequence_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference, const std::vector<Eigen::MatrixX3d>& frames,
                             const std::vector<Eigen::MatrixX3d>& results, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const std::vector<std::string>& frame_names, const SequenceReport& report,
                             const std::string& command) {
  const size_t count = frames.size();
  if (results.size() != count || frame_names.size() != count || count == 0) {
    throw ArgumentError("sequence report: " + std::to_string(count) + " frames, " + std::to_string(results.size()) +
                        " results and " + std::to_string(frame_names.size()) + " names");
  }
  const double diagonal = report.bounding_box_diagonal;
  ReportDocument document("correct-sequence", "posekit correct-sequence", command, faces, diagonal);
  const std::vector<int> reference_faces = self_intersecting_faces(reference, faces);
  const AdjacencyLists neighbours = vertex_neighbours(faces, static_cast<int>(reference.rows()));

  // The costly part, every frame's intersection tests, runs in parallel; the document is filled in order.
  std::vector<std::vector<int>> target_faces(count);
  std::vector<std::vector<int>> result_faces(count);
  std::vector<Eigen::VectorXd> moved(count);
  tbb::parallel_for(size_t{0}, count, [&](size_t i) {
    target_faces[i] = self_intersecting_faces(frames[i], faces);
    result_faces[i] = results[i] == frames[i] ? target_faces[i] : self_intersecting_faces(results[i], faces);
    moved[i] = moved_fraction(frames[i], results[i], diagonal);
  });

  double largest_move = 0.0;
  for (const Eigen::VectorXd& m : moved) largest_move = std::max(largest_move, m.maxCoeff());
  Panel reference_panel{"reference", std::nullopt, {}};
  Panel target_panel{"target", std::nullopt, {}};
  Panel result_panel{"result", ColourMap{"moved from the target", largest_move, kDiagonalUnit}, {}};
  Plot target_counts{"new intersecting faces of the target", {}};
  Plot result_counts{"new intersecting faces of the result", {}};
  Plot moves{"largest move from the target, % of the diagonal", {}};
  const int reference_pose = document.add_pose(reference);
  for (size_t i = 0; i < count; ++i) {
    document.frame_names.push_back(frame_names[i]);
    document.frame_regions.push_back(moved_regions(moved[i], neighbours, results[i]));
    reference_panel.frames.push_back({reference_pose, {}, intersection_sets(reference_faces, reference_faces), {}, {}});
    target_panel.frames.push_back({document.add_pose(frames[i]), {}, intersection_sets(target_faces[i], reference_faces), {}, {}});
    result_panel.frames.push_back(
        {document.add_pose(results[i]), moved[i], intersection_sets(result_faces[i], reference_faces), {}, {}});
    target_counts.values.push_back(static_cast<double>(new_intersecting_faces(target_faces[i], reference_faces).size()));
    result_counts.values.push_back(static_cast<double>(new_intersecting_faces(result_faces[i], reference_faces).size()));
    moves.values.push_back(100.0 * moved[i].maxCoeff());
  }
  document.panels = {std::move(reference_panel), std::move(target_panel), std::move(result_panel)};
  document.plots = {std::move(target_counts), std::move(result_counts), std::move(moves)};

  document.add_summary("frames", std::to_string(count));
  document.add_summary("corrected", std::to_string(report.corrected_frames) + " (" +
                                        std::to_string(report.carried_frames) + " by the previous frame's correction)");
  document.add_summary("frames moved from their target", std::to_string(report.touched_frames));
  document.add_summary("frames with new intersecting faces", std::to_string(report.frames_with_new_faces));
  document.add_summary("acceleration over the target's, p99 / max",
                       format_number(report.coherence.acceleration_p99_ratio) + " / " +
                           format_number(report.coherence.acceleration_max_ratio));
  document.add_summary("time", format_number(report.seconds) + " s");
  return document;
}

}  // namespace posekit::report
