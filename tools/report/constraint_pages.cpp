#include "job_pages.hpp"
#include "pose_highlights.hpp"

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <algorithm>

namespace posekit::report {
namespace {

std::vector<Marker> markers_at(const PointConstraints& constraints, const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                               const std::string& what) {
  std::vector<Marker> markers;
  for (size_t i = 0; i < constraints.vertices.size(); ++i) {
    const int vertex = constraints.vertices[i];
    markers.push_back({pose.row(vertex).transpose(), what + " " + std::to_string(i) + ": vertex " + std::to_string(vertex)});
  }
  return markers;
}

std::vector<Marker> markers_at_positions(const PointConstraints& constraints, const std::string& what) {
  std::vector<Marker> markers;
  for (size_t i = 0; i < constraints.vertices.size(); ++i) {
    markers.push_back({constraints.positions.row(static_cast<Eigen::Index>(i)).transpose(),
                       what + " " + std::to_string(i) + ": position of vertex " + std::to_string(constraints.vertices[i])});
  }
  return markers;
}

void check_markers(const PointConstraints& constraints, Eigen::Index vertex_count) {
  if (constraints.positions.rows() != static_cast<Eigen::Index>(constraints.vertices.size())) {
    throw ArgumentError("report: " + std::to_string(constraints.vertices.size()) + " constrained vertices with " +
                        std::to_string(constraints.positions.rows()) + " positions");
  }
  for (const int v : constraints.vertices) {
    if (v < 0 || v >= vertex_count) throw ArgumentError("report: constrained vertex " + std::to_string(v) + " out of range");
  }
}

}  // namespace

ReportDocument deformation_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference, const std::vector<Eigen::MatrixX3d>& results,
                                const std::vector<std::string>& result_names, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const std::vector<PointConstraints>& constraints, const std::string& command) {
  if (results.empty() || result_names.size() != results.size()) {
    throw ArgumentError("deformation report: " + std::to_string(results.size()) + " results and " +
                        std::to_string(result_names.size()) + " names");
  }
  for (const PointConstraints& set : constraints) check_markers(set, reference.rows());
  const double diagonal = bounding_box_diagonal(reference);
  ReportDocument document("deform", "posekit deform", command, faces, diagonal);
  document.frame_names = result_names;
  std::vector<Marker> handles;
  std::vector<Marker> goals;
  for (size_t s = 0; s < constraints.size(); ++s) {
    const std::string what = constraints.size() > 1 ? "constraint set " + std::to_string(s + 1) + ", point" : "constraint";
    const std::vector<Marker> on_reference = markers_at(constraints[s], reference, what);
    const std::vector<Marker> positions = markers_at_positions(constraints[s], what);
    handles.insert(handles.end(), on_reference.begin(), on_reference.end());
    goals.insert(goals.end(), positions.begin(), positions.end());
  }
  const int reference_pose = document.add_pose(reference);
  Panel reference_panel{"reference, constrained vertices", std::nullopt, {}};
  std::vector<Eigen::VectorXd> moved;
  double largest = 0.0;
  for (const Eigen::MatrixX3d& result : results) {
    moved.push_back(moved_fraction(reference, result, diagonal));
    largest = std::max(largest, moved.back().maxCoeff());
  }
  Panel result_panel{"result, constraint positions", ColourMap{"moved from the reference", largest, kDiagonalUnit}, {}};
  for (size_t i = 0; i < results.size(); ++i) {
    reference_panel.frames.push_back({reference_pose, {}, {}, handles, {}});
    result_panel.frames.push_back({document.add_pose(results[i]), moved[i], {}, goals, {}});
  }
  document.panels = {std::move(reference_panel), std::move(result_panel)};
  document.add_summary("constraints", std::to_string(goals.size()));
  double residual = 0.0;
  for (size_t s = 0; s < constraints.size(); ++s) {
    // The first set is met by the first result, a second (deform --to) by the last.
    const Eigen::MatrixX3d& result = s == 0 ? results.front() : results.back();
    for (size_t i = 0; i < constraints[s].vertices.size(); ++i) {
      residual = std::max(residual, (result.row(constraints[s].vertices[i]) -
                                     constraints[s].positions.row(static_cast<Eigen::Index>(i)))
                                        .norm());
    }
  }
  document.add_summary("largest constraint residual", format_number(100.0 * residual / diagonal) + " % of the diagonal");
  return document;
}

ReportDocument registration_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& scan_points, const PointConstraints& features,
                                 const std::string& command) {
  check_markers(features, reference.rows());
  const double diagonal = bounding_box_diagonal(reference);
  ReportDocument document("register", "posekit register", command, faces, diagonal);
  document.frame_names = {"result"};
  document.panels.push_back({"reference, feature vertices", std::nullopt,
                             {{document.add_pose(reference), {}, {}, markers_at(features, reference, "feature"), {}}}});
  document.panels.push_back({"fitted mesh, scan points and feature positions", std::nullopt,
                             {{document.add_pose(result), {}, {}, markers_at_positions(features, "feature"), scan_points}}});
  document.add_summary("scan points", std::to_string(scan_points.rows()));
  document.add_summary("features", std::to_string(features.vertices.size()));
  return document;
}

}  // namespace posekit::report
