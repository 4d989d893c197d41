// The loop the region-by-region repairs share: grow regions around the candidate's new
// intersecting faces, let the stage propose a change for each, and keep a proposal that leaves
// fewer new faces. Stages differ only in how far regions grow, how many rounds they take and what
// they propose.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"

#include <functional>
#include <optional>
#include <vector>

namespace posekit::detail {

struct RegionSweep {
  /// One pass per entry: the regions are the connected sets of vertices within this many rings of
  /// the new faces' corners.
  std::vector<int> seed_rings{1};
  int rounds = 1;                   ///< the passes repeat while a round keeps something
  double largest_fraction = 1.0;    ///< regions of more vertices than this fraction of the pose are left alone
  bool link_intersecting = false;   ///< sets whose faces intersect each other form one region
};

/// A stage's proposal for one region (sorted vertex indices) of `current`: a probe
/// (current.probe(pose)) with fewer new faces than `current`, or none.
using RegionRepair = std::function<std::optional<Probe>(const std::vector<int>& region, const Candidate& current)>;

struct SweepOutcome {
  int regions = 0;   ///< proposals kept
  int vertices = 0;  ///< vertices they moved, each counted once
};

/// Sweeps the regions of `candidate` as `sweep` says, keeping every proposal of `repair` that leaves
/// fewer new faces; a region no longer touching a new face (an earlier one freed it) is skipped.
SweepOutcome sweep_regions(Candidate& candidate, const CorrectionContext& context, const RegionSweep& sweep,
                           const RegionRepair& repair);

}  // namespace posekit::detail
