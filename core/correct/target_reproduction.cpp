#include "correct/target_reproduction.hpp"

#include "correct/repair_stage.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <iterator>

#include <algorithm>
#include <utility>

namespace posekit::detail {

Eigen::VectorXd correction_weights(const std::vector<char>& corrected, const AdjacencyLists& neighbours,
                                   int keep_rings, int blend_rings) {
  if (keep_rings < 0 || blend_rings < 0) throw ArgumentError("reproduction rings must be >= 0");
  const int vertex_count = neighbours.item_count();
  if (static_cast<int>(corrected.size()) != vertex_count) {
    throw ArgumentError("correction flags for " + std::to_string(corrected.size()) + " vertices, mesh of " +
                        std::to_string(vertex_count));
  }
  const int reach = keep_rings + blend_rings;
  const std::vector<int> distance = ring_distances(corrected, neighbours, reach);
  Eigen::VectorXd weights(vertex_count);
  for (int v = 0; v < vertex_count; ++v) {
    const int d = distance[static_cast<size_t>(v)];
    if (d < 0) {
      weights(v) = 0.0;
    } else if (d <= keep_rings) {
      weights(v) = 1.0;
    } else {
      // Smoothstep from 1 at keep_rings to 0 one ring past the band.
      const double s = static_cast<double>(d - keep_rings) / (blend_rings + 1);
      weights(v) = 1.0 - s * s * (3.0 - 2.0 * s);
    }
  }
  return weights;
}

Eigen::MatrixX3d blend_towards_target(const Eigen::Ref<const Eigen::MatrixX3d>& integrated,
                                      const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                      const Eigen::VectorXd& weights) {
  if (integrated.rows() != target.rows() || weights.size() != target.rows()) {
    throw ArgumentError("blend of poses and weights of different sizes");
  }
  Eigen::MatrixX3d blended = integrated - target;
  blended.array().colwise() *= weights.array();
  return blended + target;
}

Eigen::MatrixX3d with_shape_of(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                               const Eigen::Ref<const Eigen::MatrixX3d>& shape,
                               const std::vector<char>& region, const AdjacencyLists& neighbours) {
  std::vector<int> unknown_of(region.size(), -1);
  std::vector<int> vertices;
  for (int v = 0; v < static_cast<int>(region.size()); ++v) {
    if (region[static_cast<size_t>(v)] == 0) continue;
    unknown_of[static_cast<size_t>(v)] = static_cast<int>(vertices.size());
    vertices.push_back(v);
  }
  const auto size = static_cast<Eigen::Index>(vertices.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(size, 3);
  for (Eigen::Index i = 0; i < size; ++i) {
    const int v = vertices[static_cast<size_t>(i)];
    entries.emplace_back(i, i, static_cast<double>(neighbours[v].size()));
    for (int w : neighbours[v]) {
      const int j = unknown_of[static_cast<size_t>(w)];
      if (j >= 0) {
        entries.emplace_back(i, j, -1.0);
      } else {
        rhs.row(i) += pose.row(w) - shape.row(w);
      }
    }
  }
  Eigen::SparseMatrix<double> laplacian(size, size);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  Eigen::MatrixX3d reshaped = pose;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
  const Eigen::MatrixX3d offsets =
      solver.info() == Eigen::Success ? Eigen::MatrixX3d(solver.solve(rhs)) : Eigen::MatrixX3d::Zero(size, 3);
  for (Eigen::Index i = 0; i < size; ++i) {
    const int v = vertices[static_cast<size_t>(i)];
    reshaped.row(v) = shape.row(v) + (offsets.row(i).allFinite() ? Eigen::RowVector3d(offsets.row(i)) : Eigen::RowVector3d::Zero());
  }
  return reshaped;
}

Reproduction reproduce_target(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                              const Eigen::Ref<const Eigen::MatrixX3d>& target, std::vector<char> kept,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces, const AdjacencyLists& neighbours,
                              const ReproductionSettings& settings, const FaceTest& new_faces,
                              const std::vector<int>& allowed) {
  for (int attempt = 0; attempt < settings.attempts; ++attempt) {
    const Eigen::VectorXd weights = correction_weights(kept, neighbours, settings.keep_rings, settings.blend_rings);
    Eigen::MatrixX3d reproduced = blend_towards_target(result, target, weights);
    const std::vector<int> added = new_intersecting_faces(new_faces(reproduced), allowed);
    if (added.empty()) {
      Reproduction done;
      done.reproduced_vertices = static_cast<int>((weights.array() == 0.0).count());
      done.pose = std::move(reproduced);
      return done;
    }
    const std::vector<char> around =
        within_rings(face_vertices(added, faces, kept.size()), neighbours, settings.widening_rings);
    for (size_t v = 0; v < kept.size(); ++v) kept[v] = kept[v] != 0 || around[v] != 0 ? 1 : 0;
  }
  return {};
}

namespace {

// The final reproduction starts from the target's intersecting faces alone, so it widens one ring
// at a time around what it would add, for longer (real poses needed two to ten rounds).
constexpr int kFinalReproductionAttempts = 12;

// After the repairs, which keep or move whole regions, only the target's own new intersections
// and what is still new need the candidate's positions; the rest of the pose can be the target
// again wherever that adds no intersection.
class FinalReproductionStage final : public RepairStage {
 public:
  FinalReproductionStage()
      : RepairStage({"final-reproduction",
                     "give back the target's positions away from its own intersections and what is still new"},
                    kEveryScope) {}

  bool enabled(const CorrectionOptions& options) const override {
    return RepairStage::enabled(options) && options.reproduction_rings >= 0;
  }

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    return current.pose() != context.target;
  }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    std::vector<int> kept_faces =
        new_intersecting_faces(faces_in_pairs(context.target_pairs), context.reference_intersecting);
    kept_faces.insert(kept_faces.end(), current.new_faces().begin(), current.new_faces().end());
    const std::vector<char> kept = face_vertices(kept_faces, context.faces, static_cast<size_t>(context.vertex_count()));
    ReproductionSettings settings;
    settings.blend_rings = context.options.blend_rings;
    settings.widening_rings = 1;
    settings.attempts = kFinalReproductionAttempts;
    const FaceTest new_faces = [&](const Eigen::Ref<const Eigen::MatrixX3d>& pose) {
      return current.new_faces_if(pose);
    };
    Reproduction reproduction = reproduce_target(current.pose(), context.target, kept, context.faces,
                                                 context.neighbours, settings, new_faces, current.new_faces());
    if (!reproduction.pose) return std::nullopt;
    const int before = static_cast<int>(differing_vertices(current.pose(), context.target).size());
    Candidate reproduced = current;
    reproduced.move_to(*reproduction.pose);
    const int after = static_cast<int>(differing_vertices(reproduced.pose(), context.target).size());
    report.regions = 1;
    report.vertices = before - after;
    report.details = {{"reproduced_vertices", reproduction.reproduced_vertices}};
    report.note = std::to_string(before - after) + " more vertices given the target's positions";
    return reproduced;
  }
};

}  // namespace

std::unique_ptr<RepairStage> make_final_reproduction_stage() { return std::make_unique<FinalReproductionStage>(); }

}  // namespace posekit::detail
