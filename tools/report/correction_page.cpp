#include "job_pages.hpp"
#include "pose_highlights.hpp"

#include <posekit/self_intersections.hpp>

namespace posekit::report {
namespace {

Table stage_table(const CorrectionReport& report) {
  Table table{"repair stages", {"stage", "ran", "kept", "new faces before", "after", "regions", "vertices", "seconds", "note"}, {}};
  for (const StageReport& stage : report.stages) {
    table.rows.push_back({stage.name, stage.ran ? "yes" : "no: " + stage.skipped, stage.kept ? "yes" : "",
                          stage.ran ? std::to_string(stage.new_faces_before) : "",
                          stage.ran ? std::to_string(stage.new_faces_after) : "",
                          stage.ran ? std::to_string(stage.regions) : "", stage.ran ? std::to_string(stage.vertices) : "",
                          stage.ran ? format_number(stage.seconds) : "", stage.note});
  }
  return table;
}

}  // namespace

ReportDocument correction_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                               const Eigen::Ref<const Eigen::MatrixX3d>& target,
                               const Eigen::Ref<const Eigen::MatrixX3d>& result,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces, const CorrectionReport& report,
                               const std::string& command) {
  const double diagonal = report.result.bounding_box_diagonal;
  ReportDocument document("correct", "posekit correct", command, faces, diagonal);
  const std::vector<int> reference_faces = self_intersecting_faces(reference, faces);
  const std::vector<int> target_faces = self_intersecting_faces(target, faces);
  const std::vector<int> result_faces = self_intersecting_faces(result, faces);
  const Eigen::VectorXd moved = moved_fraction(target, result, diagonal);

  document.frame_names = {"result"};
  document.frame_regions = {
      moved_regions(moved, vertex_neighbours(faces, static_cast<int>(result.rows())), result)};
  PanelFrame reference_frame{document.add_pose(reference), {}, intersection_sets(reference_faces, reference_faces), {}, {}};
  PanelFrame target_frame{document.add_pose(target), {}, intersection_sets(target_faces, reference_faces), {}, {}};
  PanelFrame result_frame{document.add_pose(result), moved, intersection_sets(result_faces, reference_faces), {}, {}};
  document.panels.push_back({"reference", std::nullopt, {std::move(reference_frame)}});
  document.panels.push_back({"target", std::nullopt, {std::move(target_frame)}});
  document.panels.push_back({"result", ColourMap{"moved from the target", std::max(moved.maxCoeff(), 0.0), kDiagonalUnit},
                             {std::move(result_frame)}});

  const ResultReport& r = report.result;
  document.add_summary("intersecting faces of the target", std::to_string(r.target_intersecting_faces));
  document.add_summary("new intersecting faces of the result", std::to_string(r.new_intersecting_faces));
  document.add_summary("vertices moved from the target", std::to_string(r.changed_vertices) + " of " +
                                                          std::to_string(report.vertices));
  document.add_summary("median distance to the target",
                       format_number(diagonal > 0.0 ? 100.0 * r.median_distance_to_target / diagonal : 0.0) +
                           " % of the diagonal");
  document.add_summary("stretched faces", std::to_string(r.stretched_faces) + " (" +
                                              std::to_string(r.strongly_stretched_faces) + " over 3x)");
  document.add_summary("time", format_number(report.seconds) + " s on " + report.device);
  document.tables.push_back(stage_table(report));
  return document;
}

}  // namespace posekit::report
