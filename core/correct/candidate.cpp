#include "correct/candidate.hpp"

#include "correct/correction_context.hpp"

#include <posekit/correct.hpp>
#include <posekit/self_intersections.hpp>

#include <utility>

namespace posekit::detail {

Candidate::Candidate(const Eigen::Ref<const Eigen::MatrixX3d>& pose, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                     const std::vector<int>& allowed)
    : Candidate(pose, faces, allowed, self_intersecting_face_pairs(pose, faces)) {}

Candidate::Candidate(const Eigen::Ref<const Eigen::MatrixX3d>& pose, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                     const std::vector<int>& allowed,
                     FacePairs known)
    : tracker_(pose, faces, std::move(known)), allowed_(&allowed) {
  new_faces_ = new_intersecting_faces(faces_in_pairs(tracker_.pairs()), allowed);
}

Probe Candidate::probe(Eigen::MatrixX3d changed) const {
  Probe probe;
  probe.pairs = tracker_.pairs_if(changed);
  probe.new_faces = new_intersecting_faces(faces_in_pairs(probe.pairs), *allowed_);
  probe.pose = std::move(changed);
  return probe;
}

void Candidate::accept(Probe probe) {
  tracker_.update(probe.pose, std::move(probe.pairs));
  new_faces_ = std::move(probe.new_faces);
}

bool better(const Candidate& a, const Candidate& b, const CorrectionContext& context) {
  if (a.new_face_count() != b.new_face_count()) return a.new_face_count() < b.new_face_count();
  const double a_median = median_distance(a.pose(), context.target);
  const double b_median = median_distance(b.pose(), context.target);
  const double near = context.options.separation_tolerance * context.diagonal;
  if ((a_median <= near) != (b_median <= near)) return a_median <= near;
  const int a_stretched = context.stretch.count(a.pose());
  const int b_stretched = context.stretch.count(b.pose());
  if (a_stretched != b_stretched) return a_stretched < b_stretched;
  return a_median < b_median;
}

double median_distance(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                       const Eigen::Ref<const Eigen::MatrixX3d>& target) {
  return DriftSummary::of(pose - target).median;
}

std::vector<int> differing_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& a,
                                    const Eigen::Ref<const Eigen::MatrixX3d>& b) {
  std::vector<int> differing;
  for (Eigen::Index v = 0; v < a.rows(); ++v) {
    if (a.row(v) != b.row(v)) differing.push_back(static_cast<int>(v));
  }
  return differing;
}

}  // namespace posekit::detail
