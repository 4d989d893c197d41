// A correction context for testing one stage on its own: the poses in their own frame, the CPU
// device and the default options.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"

#include <posekit/cpu_device.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

namespace posekit::detail::testing {

struct StageFixture {
  StageFixture(const Eigen::MatrixX3d& reference_pose, const Eigen::MatrixX3d& target_pose, const Eigen::MatrixX3i& mesh_faces,
               const CorrectionOptions& correction_options = {})
      : reference(reference_pose),
        target(target_pose),
        faces(mesh_faces),
        options(correction_options),
        device(make_cpu_device()),
        context(make_context(reference, target, faces, *device, options, CorrectionScope::whole_pose, {})) {}

  /// `pose` as a candidate of this context.
  Candidate candidate(const Eigen::MatrixX3d& pose) const {
    return Candidate(pose, faces, context.reference_intersecting);
  }

  Eigen::MatrixX3d reference;
  Eigen::MatrixX3d target;
  Eigen::MatrixX3i faces;
  CorrectionOptions options;
  std::unique_ptr<Device> device;
  CorrectionContext context;
};

/// The stage's own figure `name` from its report's details; a failure and -1 where it is missing.
inline double stage_detail(const StageReport& report, const std::string& name) {
  const auto found = std::find_if(report.details.begin(), report.details.end(),
                                  [&](const auto& entry) { return entry.first == name; });
  EXPECT_NE(found, report.details.end()) << name;
  return found == report.details.end() ? -1.0 : found->second;
}

}  // namespace posekit::detail::testing
