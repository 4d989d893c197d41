#include "job_pages.hpp"

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <algorithm>

namespace posekit::report {

ReportDocument interpolation_page(const PoseInterpolator& interpolator, const std::vector<std::string>& pose_names,
                                  const std::vector<Eigen::VectorXd>& weights, const std::vector<Eigen::MatrixX3d>& results,
                                  const std::vector<std::string>& output_names, const std::string& command) {
  const PoseSet& poses = interpolator.poses();
  if (static_cast<int>(pose_names.size()) != poses.pose_count() || weights.size() != results.size() ||
      output_names.size() != results.size()) {
    throw ArgumentError("interpolation report: " + std::to_string(pose_names.size()) + " names for " +
                        std::to_string(poses.pose_count()) + " poses, " + std::to_string(weights.size()) + " weights for " +
                        std::to_string(results.size()) + " results");
  }
  const double diagonal = bounding_box_diagonal(poses.pose(0));
  ReportDocument document("interpolate", "posekit interpolate", command, poses.faces(), diagonal);
  document.frame_names = {"result"};
  for (int k = 0; k < poses.pose_count(); ++k) {
    document.panels.push_back({pose_names[static_cast<size_t>(k)], std::nullopt, {{document.add_pose(poses.pose(k)), {}, {}, {}, {}}}});
  }
  std::vector<Eigen::VectorXd> errors;
  double largest = 0.0;
  for (size_t i = 0; i < results.size(); ++i) {
    errors.push_back(100.0 * interpolator.vertex_edge_length_errors(results[i], weights[i]));  // in percent
    largest = std::max(largest, errors.back().maxCoeff());
  }
  Table table{"in-between poses", {"output", "weights", "edge-length error p99", "dihedral error p99 (degrees)",
                                   "collapsed faces", "flipped faces"}, {}};
  for (size_t i = 0; i < results.size(); ++i) {
    const InterpolationError error = interpolator.error(results[i], weights[i]);
    std::string weight_text;
    for (Eigen::Index k = 0; k < weights[i].size(); ++k) weight_text += (k ? ", " : "") + format_number(weights[i](k));
    document.panels.push_back({output_names[i], ColourMap{"edge-length error", largest, "%"},
                               {{document.add_pose(results[i]), errors[i], {}, {}, {}}}});
    table.rows.push_back({output_names[i], weight_text, format_number(100.0 * error.edge_length.p99) + " %",
                          format_number(error.dihedral_degrees.p99), std::to_string(error.collapsed_faces),
                          std::to_string(error.flipped_faces)});
  }
  document.add_summary("input poses", std::to_string(poses.pose_count()));
  document.add_summary("in-between poses", std::to_string(results.size()));
  document.add_summary("vertices", std::to_string(poses.vertex_count()));
  document.add_summary("largest relative edge-length error", format_number(largest) + " %");
  document.tables.push_back(std::move(table));
  return document;
}

}  // namespace posekit::report
