// The report of each job: which panels, colours, regions, plots and tables it shows.
#pragma once

#include "report_document.hpp"

#include <posekit/blend_files.hpp>
#include <posekit/correct.hpp>
#include <posekit/correct_sequence.hpp>
#include <posekit/interpolate.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace posekit::report {

/// A correction: reference, target (its intersecting faces) and result (its displacement from the
/// target as a colour map, any new intersecting faces), the regions it moved and the stage table.
ReportDocument correction_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                               const Eigen::Ref<const Eigen::MatrixX3d>& target,
                               const Eigen::Ref<const Eigen::MatrixX3d>& result,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces, const CorrectionReport& report,
                               const std::string& command);

/// A corrected sequence: per frame the target and the result as in correction_page(), with the
/// per-frame counts plotted over time. `results` holds one pose per frame (a failed frame: its target).
ReportDocument sequence_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference, const std::vector<Eigen::MatrixX3d>& frames,
                             const std::vector<Eigen::MatrixX3d>& results, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const std::vector<std::string>& frame_names, const SequenceReport& report,
                             const std::string& command);

/// Interpolation: every input pose, then every in-between with its relative edge-length error per
/// vertex as a colour map. `pose_names` name the inputs, `output_names` and `weights` the in-betweens.
ReportDocument interpolation_page(const PoseInterpolator& interpolator, const std::vector<std::string>& pose_names,
                                  const std::vector<Eigen::VectorXd>& weights, const std::vector<Eigen::MatrixX3d>& results,
                                  const std::vector<std::string>& output_names, const std::string& command);

/// A deformation: the reference with the constrained vertices marked, and the result (one frame per
/// pose of `results`, named by `result_names`) with the constraint positions marked and its
/// displacement from the reference as a colour map.
ReportDocument deformation_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference, const std::vector<Eigen::MatrixX3d>& results,
                                const std::vector<std::string>& result_names, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const std::vector<PointConstraints>& constraints, const std::string& command);

/// A partial registration: the reference with the feature vertices marked, and the fitted mesh with
/// the scan's points and the features' positions on the scan.
ReportDocument registration_page(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& scan_points, const PointConstraints& features,
                                 const std::string& command);

}  // namespace posekit::report
