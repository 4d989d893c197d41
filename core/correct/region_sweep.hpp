// The loop the region-by-region repairs share: grow regions around the faces that are wrong (by
// default the candidate's new intersecting faces), let the stage propose a change for each, and
// keep a proposal that improves the candidate. Stages differ only in what is wrong, how far regions
// grow, how many rounds they take and what they propose.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"

#include <functional>
#include <optional>
#include <vector>

namespace posekit::detail {

/// What a sweep repairs: the faces it grows regions around, and when a proposal is an improvement.
struct SweepGoal {
  std::function<std::vector<int>(const Candidate&)> faces_to_mend;
  std::function<bool(const Probe& proposal, const Candidate& current)> improves;
};

/// The faces to mend are the new intersecting faces; a proposal improves by having fewer.
SweepGoal fewer_new_faces();

struct RegionSweep {
  /// One pass per entry: the regions are the connected sets of vertices within this many rings of
  /// the new faces' corners.
  std::vector<int> seed_rings{1};
  int rounds = 1;                   ///< the passes repeat while a round keeps something
  double largest_fraction = 1.0;    ///< regions of more vertices than this fraction of the pose are left alone
  bool link_intersecting = false;   ///< sets whose faces intersect each other form one region
  SweepGoal goal = fewer_new_faces();
};

/// A stage's proposal for one region (sorted vertex indices) of `current`: a probe
/// (current.probe(pose)) that improves `current` by the sweep's goal, or none.
using RegionRepair = std::function<std::optional<Probe>(const std::vector<int>& region, const Candidate& current)>;

struct SweepOutcome {
  int regions = 0;   ///< proposals kept
  int vertices = 0;  ///< vertices they moved, each counted once
};

/// Sweeps the regions of `candidate` as `sweep` says, keeping every proposal of `repair` that
/// improves it by the goal; a region no longer touching a face to mend (an earlier one mended it)
/// is skipped.
SweepOutcome sweep_regions(Candidate& candidate, const CorrectionContext& context, const RegionSweep& sweep,
                           const RegionRepair& repair);

}  // namespace posekit::detail
