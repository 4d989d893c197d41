// A pose on the repair ladder and what is wrong with it: the faces that intersect and are not the
// reference's. It is tested whole once; a changed pose is tested only where it moved (the one
// intersection oracle every stage shares), and one rule says which of two candidates is better.
#pragma once

#include <posekit/self_intersection_tracker.hpp>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace posekit::detail {

/// A changed pose with its intersecting pairs and new faces, tested but not yet kept.
struct Probe {
  Eigen::MatrixX3d pose;
  FacePairs pairs;
  std::vector<int> new_faces;  ///< sorted
};

class Candidate {
 public:
  /// `pose` (#V by 3) of `faces` tested whole, or with its `known` pairs; `allowed` (sorted) are the
  /// reference's intersecting faces, which do not count as new, and must outlive it.
  Candidate(const Eigen::Ref<const Eigen::MatrixX3d>& pose, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
            const std::vector<int>& allowed);
  Candidate(const Eigen::Ref<const Eigen::MatrixX3d>& pose, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
            const std::vector<int>& allowed,
            FacePairs known);

  const Eigen::MatrixX3d& pose() const { return tracker_.vertices(); }
  const FacePairs& pairs() const { return tracker_.pairs(); }
  const std::vector<int>& new_faces() const { return new_faces_; }
  int new_face_count() const { return static_cast<int>(new_faces_.size()); }
  const Eigen::MatrixX3i& faces() const { return tracker_.faces(); }

  /// `changed` (#V by 3) tested where it differs from pose(). Safe from several threads at once.
  Probe probe(Eigen::MatrixX3d changed) const;
  /// New faces `changed` would have.
  std::vector<int> new_faces_if(const Eigen::Ref<const Eigen::MatrixX3d>& changed) const {
    return probe(changed).new_faces;
  }
  /// Takes the probed pose (probed from this candidate as it is now).
  void accept(Probe probe);
  /// Moves to `changed`, tested where it differs.
  void move_to(const Eigen::Ref<const Eigen::MatrixX3d>& changed) { accept(probe(changed)); }

 private:
  SelfIntersectionTracker tracker_;
  const std::vector<int>* allowed_;
  std::vector<int> new_faces_;
};

struct CorrectionContext;

/// The one rule for two candidates: fewer new intersecting faces; between equals, the one whose
/// median distance to the context's target is within the separation tolerance (of the diagonal);
/// then fewer faces the correction stretched (StretchMeasure); then the smaller median distance.
bool better(const Candidate& a, const Candidate& b, const CorrectionContext& context);

/// Median distance between corresponding rows of `pose` and `target`.
double median_distance(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                       const Eigen::Ref<const Eigen::MatrixX3d>& target);

/// Vertices where `a` and `b` differ, ascending.
std::vector<int> differing_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& a,
                                    const Eigen::Ref<const Eigen::MatrixX3d>& b);

}  // namespace posekit::detail
