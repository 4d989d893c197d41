// What every stage of a correction shares: the two poses in the unit-sphere frame, the connectivity
// and its adjacency, the reference's own intersections, the device, the options, where the run is
// nested, and (once the field correction has run) the field's result and path lines.
#pragma once

#include "correct/path_lines.hpp"
#include "correct/stretch_measure.hpp"
#include "correct/vertex_classification.hpp"
#include "correct/vertex_trajectories.hpp"

#include <posekit/correct.hpp>
#include <posekit/device.hpp>
#include <posekit/self_intersection_tracker.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace posekit::detail {

/// Where a correction runs. Nested runs (a region on its own, a leg through the halfway pose, the
/// whole pose again for less stretch) leave out the stages that would nest again, that the whole
/// pose runs after them or that cost more than they can win there; each stage says where it runs
/// (RepairStage::scopes), so no caller edits a copy of the options.
enum class CorrectionScope { whole_pose = 1, region = 2, leg = 4, stretch_retry = 8 };

/// A set of scopes, as a bit mask of CorrectionScope values.
using ScopeSet = unsigned;
constexpr ScopeSet kEveryScope = 15;
constexpr ScopeSet scope_bit(CorrectionScope scope) { return static_cast<ScopeSet>(scope); }

/// The field correction's outcome, which later stages build on (its classification is the pair
/// analysis's).
struct FieldOutcome {
  Eigen::MatrixX3d integrated;  ///< the field's end positions in its regions, the target elsewhere
  PathLines paths;              ///< the path lines every vertex took
};

/// What a correction computes from its pair of poses alone, whatever the collar: the field's key
/// frames, the pairs that intersect in its tested poses and the vertex classification, and the
/// halfway pose of the legs. Each is computed once, by the stage that first needs it, and lent to the
/// run that corrects the same pair again in the same frame with a wider collar. The options it reads
/// (key frames, intersection substeps, exclusion rings; analyze_pair in field_correction.cpp) are
/// ones that run keeps.
struct PairAnalysis {
  std::shared_ptr<const VertexTrajectories> trajectories;
  std::vector<FacePairs> tested_pairs;  ///< per tested pose, the reference first and the target last
  std::optional<VertexClassification> classification;
  std::optional<Eigen::MatrixX3d> halfway;  ///< in the frame of the context that holds it
  /// The first leg's own analysis: its pair (the reference and the halfway pose) is the same in
  /// every run of this pair, whatever the collar.
  std::shared_ptr<PairAnalysis> first_leg;
};

/// An analysis lent to a nested run of the same two poses. Where `poses_in_its_frame`, they come in
/// the frame the analysis was made in (the wider collar's run) and are not normalized again;
/// otherwise they come as the run that made it got them, and are normalized as it normalized them.
struct LentAnalysis {
  std::shared_ptr<PairAnalysis> analysis;
  bool poses_in_its_frame = false;
};

/// Holds views of the poses and faces it was made from, which must outlive it.
struct CorrectionContext {
  Eigen::Ref<const Eigen::MatrixX3d> reference;  ///< unit-sphere frame
  Eigen::Ref<const Eigen::MatrixX3d> target;     ///< unit-sphere frame
  Eigen::Ref<const Eigen::MatrixX3i> faces;
  Device& device;
  const CorrectionOptions& options;
  CorrectionScope scope;
  AdjacencyLists neighbours;                 ///< vertex one-rings
  FacePairs reference_pairs;                 ///< the reference's intersecting pairs
  FacePairs target_pairs;                    ///< the target's
  std::vector<int> reference_intersecting;   ///< faces of reference_pairs, sorted: never new
  int target_new_faces = 0;                  ///< new faces of the target itself
  double diagonal = 0;                       ///< the reference's bounding-box diagonal
  StretchMeasure stretch;                    ///< faces a candidate stretched beyond both poses
  CorrectionProgress progress;
  FieldReport* field_report = nullptr;       ///< filled by the field correction
  std::optional<FieldOutcome> field;         ///< set by the field correction
  /// Never null: the run's own, or the one a run of the same pair lent it (make_context).
  std::shared_ptr<PairAnalysis> pair_analysis = std::make_shared<PairAnalysis>();

  int vertex_count() const { return static_cast<int>(reference.rows()); }
  /// Whether a candidate with `new_faces` new intersecting faces still has at least half of the
  /// target's own: the pose is entangled throughout, not in a few places.
  bool entangled_throughout(int new_faces) const { return 2 * new_faces > target_new_faces; }
  void report_progress(const std::string& step, double fraction) const {
    if (progress) progress(step, fraction);
  }
};

/// Builds the context: adjacency, the two poses' intersecting pairs and the diagonal. `same_pair`,
/// when given, is the analysis of a run of the same two poses in the same frame: the context holds
/// it, and takes the two poses' pairs from its tested poses where it has them.
CorrectionContext make_context(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                               const Eigen::Ref<const Eigen::MatrixX3d>& target,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces, Device& device,
                               const CorrectionOptions& options,
                               CorrectionScope scope, const CorrectionProgress& progress,
                               std::shared_ptr<PairAnalysis> same_pair = nullptr);

}  // namespace posekit::detail
