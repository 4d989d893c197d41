#include "correct/contact_separation.hpp"

#include "cgal/nearest_point.hpp"

#include "correct/region_relaxation.hpp"
#include "correct/repair_stage.hpp"
#include <posekit/vertex_regions.hpp>

#include <posekit/as_rigid_as_possible.hpp>
#include <posekit/geometry.hpp>
#include <posekit/topology.hpp>
#include <posekit/winding_numbers.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <cmath>
#include <memory>
#include <optional>
#include <limits>
#include <utility>

namespace posekit::detail {
namespace {


// Rounds of pushes and relaxations at most (docs/correct.md: a pose pressed together throughout
// needed nine).
constexpr int kRounds = 20;
// A vertex that enters another part changes its winding number by one (1/2 on its own surface,
// 3/2 inside another part of the same orientation).
constexpr double kEnteredWinding = 0.5;
// Vertices this many rings from an intersecting face are tested for lying inside another part.
constexpr int kTestedRings = 2;
// The surface a part lies in is looked for this many rings around the faces it intersects.
constexpr int kPartnerRings = 6;
// Each of two parts in contact gives way by half the depth, plus this fraction of the mean edge
// length so that they part rather than touch; a face that crosses without a vertex inside moves
// back by the same amount.
constexpr double kDepthShare = 0.5;
constexpr double kClearance = 0.2;
// Passes of averaging over neighbouring pushed vertices, which differ in depth from one to the next.
constexpr int kSmoothingPasses = 2;
// Rings around the pushed vertices that follow them as-rigidly-as-possible: more drag more of the
// surface along and crease it elsewhere (docs/correct.md: two rings freed a pose three left at 144
// faces).
constexpr int kFollowingRings = 2;
// A fold is relaxed over a few rings only, and not kept where it swings a part away (unbounded, the
// relaxation towards the reference straightened a curled tail by half the diagonal).
constexpr int kFoldMargin = 6;
constexpr double kLargestFoldMove = 24.0;  // mean edge lengths

// Per vertex of `pose`, the push that takes it out of the part it lies in, for the vertices of the
// intersecting faces and those near them; zero elsewhere. `pushed` flags the vertices given one. A
// vertex lies in another part where its winding number differs by more than a half from its
// winding number in `reference`: what the reference already has (its own parts passing through
// each other, folds that turn a patch inside out) is not a contact to separate. `reference_tree` is
// the winding-number tree of `reference`.
Eigen::MatrixX3d contact_pushes(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                                const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                const WindingNumberTree& reference_tree,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const std::vector<int>& intersecting,
                                const std::vector<std::pair<int, int>>& pairs, const AdjacencyLists& neighbours,
                                const AdjacencyLists& faces_of_vertex, double clearance, std::vector<char>& pushed) {
  const auto vertex_count = static_cast<size_t>(pose.rows());
  const std::vector<char> tested = within_rings(face_vertices(intersecting, faces, vertex_count), neighbours, kTestedRings);
  std::vector<int> tested_rows;
  for (size_t v = 0; v < vertex_count; ++v) {
    if (tested[v] != 0) tested_rows.push_back(static_cast<int>(v));
  }
  const Eigen::VectorXd winding = winding_numbers(pose, faces, pose(tested_rows, Eigen::all)) -
                                  reference_tree.at(reference(tested_rows, Eigen::all));
  std::vector<char> inside(vertex_count, 0);
  for (size_t k = 0; k < tested_rows.size(); ++k) {
    if (std::abs(winding(static_cast<Eigen::Index>(k))) > kEnteredWinding) inside[static_cast<size_t>(tested_rows[k])] = 1;
  }

  std::vector<std::vector<int>> partners(static_cast<size_t>(faces.rows()));
  for (const auto& [a, b] : pairs) {
    partners[static_cast<size_t>(a)].push_back(b);
    partners[static_cast<size_t>(b)].push_back(a);
  }
  const Eigen::MatrixX3d normals = vertex_normals(pose, faces);
  const Eigen::MatrixX3d outward = face_normals(pose, faces);
  Eigen::MatrixX3d push = Eigen::MatrixX3d::Zero(pose.rows(), 3);
  pushed.assign(vertex_count, 0);
  const std::vector<std::vector<int>> parts = connected_sets(inside, neighbours);

  // Each connected set of inside vertices lies in the surface its faces intersect; its depth there
  // is the distance to that surface, among the faces it lies behind.
  tbb::parallel_for(size_t{0}, parts.size(), [&](size_t p) {
    std::vector<char> own(vertex_count, 0);
    for (int v : parts[p]) own[static_cast<size_t>(v)] = 1;
    const std::vector<char> own_faces = faces_within(within_rings(own, neighbours, 1), faces);
    std::vector<char> other(vertex_count, 0);
    for (int v : parts[p]) {
      for (int f : faces_of_vertex[v]) {
        for (int g : partners[static_cast<size_t>(f)]) {
          for (int c = 0; c < 3; ++c) other[static_cast<size_t>(faces(g, c))] = 1;
        }
      }
    }
    const std::vector<char> lying_in = faces_within(within_rings(other, neighbours, kPartnerRings), faces);
    std::vector<Eigen::Index> surface_faces;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      if (lying_in[static_cast<size_t>(f)] == 0 || own_faces[static_cast<size_t>(f)] != 0) continue;
      surface_faces.push_back(f);
    }
    for (int v : parts[p]) {
      const Eigen::RowVector3d point = pose.row(v);
      double depth = std::numeric_limits<double>::infinity();
      for (const Eigen::Index f : surface_faces) {
        const Eigen::RowVector3d nearest = detail::nearest_point_on_triangle(
            point, pose.row(faces(f, 0)), pose.row(faces(f, 1)), pose.row(faces(f, 2)));
        const Eigen::RowVector3d offset = point - nearest;
        if (offset.dot(outward.row(f)) > 0.0) continue;  // in front of that face
        depth = std::min(depth, offset.norm());
      }
      if (!std::isfinite(depth)) continue;
      push.row(v) = -(kDepthShare * depth + clearance) * normals.row(v);
      pushed[static_cast<size_t>(v)] = 1;
    }
  });
  for (int f : intersecting) {
    for (int c = 0; c < 3; ++c) {
      const int v = faces(f, c);
      if (pushed[static_cast<size_t>(v)] != 0) continue;
      push.row(v) = -clearance * normals.row(v);
      pushed[static_cast<size_t>(v)] = 1;
    }
  }
  for (int pass = 0; pass < kSmoothingPasses; ++pass) {
    Eigen::MatrixX3d averaged = push;
    for (size_t v = 0; v < vertex_count; ++v) {
      if (pushed[v] == 0) continue;
      Eigen::RowVector3d sum = push.row(static_cast<Eigen::Index>(v));
      int count = 1;
      for (int w : neighbours[static_cast<int>(v)]) {
        if (pushed[static_cast<size_t>(w)] == 0) continue;
        sum += push.row(w);
        ++count;
      }
      averaged.row(static_cast<Eigen::Index>(v)) = sum / count;
    }
    push = std::move(averaged);
  }
  return push;
}

// Rounds without a better pose after which a separation stops: it has settled.
constexpr int kRoundsWithoutProgress = 5;

// The separation of the target's contacts depends only on the context, so both places of the
// ladder share one outcome.
struct SeparationCache {
  std::optional<SeparationOutcome> outcome;
};

// Early: where the field and the first repairs freed less than half of the target's new faces, the
// pose is entangled throughout and separating its contacts, which costs a few seconds, may free it
// at once: then the costly stages have nothing left to do. Its pose is kept only when clean. Late:
// where faces remain or the candidate strayed from the target, the separation competes as is.
class ContactSeparationStage final : public RepairStage {
 public:
  ContactSeparationStage(std::shared_ptr<SeparationCache> cache, bool early)
      : RepairStage({"contact-separation",
                     "separate the target's own contacts where the correction strays from the target or faces remain"},
                    scope_bit(CorrectionScope::whole_pose) | scope_bit(CorrectionScope::stretch_retry)),
        cache_(std::move(cache)),
        early_(early) {}

  bool enabled(const CorrectionOptions& options) const override {
    return RepairStage::enabled(options) && options.reproduction_rings >= 0;
  }

  // The two places keep the shared outcome by different rules.
  std::string repair() const override { return info().name + (early_ ? " (early)" : " (late)"); }

  bool wanted(const Candidate& current, const CorrectionContext& context) const override {
    if (early_) return context.entangled_throughout(current.new_face_count());
    return current.new_face_count() > 0 ||
           median_distance(current.pose(), context.target) > context.options.separation_tolerance * context.diagonal;
  }

  std::optional<Candidate> run(const Candidate& /*current*/, CorrectionContext& context, StageReport& report) override {
    if (!cache_->outcome) {
      cache_->outcome = separate_contacts(
          context, Candidate(context.target, context.faces, context.reference_intersecting, context.target_pairs));
    }
    const SeparationOutcome& outcome = *cache_->outcome;
    report.details = {{"rounds", outcome.rounds}, {"new_faces", outcome.best.new_face_count()}};
    report.regions = 1;
    report.vertices = static_cast<int>(differing_vertices(outcome.best.pose(), context.target).size());
    if (early_ && outcome.best.new_face_count() > 0) return std::nullopt;
    report.note = "the target with its own contacts separated (" + std::to_string(outcome.rounds) +
                  " rounds), in place of the correction";
    return outcome.best;
  }

 private:
  std::shared_ptr<SeparationCache> cache_;
  bool early_;
};

// The same pushes on the candidate itself, for the few contacts the stages before left: a face
// pressed into another (or into one the reference already has intersecting) moves back out of it,
// and its surroundings follow the candidate's own shape.
class ContactPushStage final : public RepairStage {
 public:
  ContactPushStage()
      : RepairStage({"contact-push", "push the candidate's remaining contacts apart, its surroundings following"},
                    kEveryScope) {}

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& report) override {
    SeparationOutcome outcome = separate_contacts(context, current);
    report.details = {{"rounds", outcome.rounds}};
    report.regions = 1;
    report.vertices = static_cast<int>(differing_vertices(outcome.best.pose(), current.pose()).size());
    if (report.vertices == 0) return std::nullopt;
    report.note = std::to_string(report.vertices) + " vertices pushed out of the parts they lay in (" +
                  std::to_string(outcome.rounds) + " rounds)";
    return std::move(outcome.best);
  }
};

}  // namespace

SeparationOutcome separate_contacts(const CorrectionContext& context, Candidate start) {
  const Eigen::Ref<const Eigen::MatrixX3i>& faces = context.faces;
  const AdjacencyLists& neighbours = context.neighbours;
  const AdjacencyLists faces_of_vertex = vertex_faces(faces, context.vertex_count());
  const Eigen::MatrixX3d rest = start.pose();  // the shape the surroundings keep
  const double mean_edge = edge_lengths(rest, edge_map(faces).edges).mean();
  RelaxationLimits fold_limits;
  fold_limits.widest_margin = kFoldMargin;
  fold_limits.largest_move = kLargestFoldMove * mean_edge;

  Candidate pose = std::move(start);
  SeparationOutcome out{pose, 0, pose.new_face_count()};
  int stale_rounds = 0;
  std::optional<WindingNumberTree> reference_tree;
  const auto keep_if_better = [&] {
    if (pose.new_face_count() >= out.best.new_face_count()) return false;
    out.best = pose;
    return true;
  };
  for (int round = 0; round < kRounds && pose.new_face_count() > 0 && stale_rounds < kRoundsWithoutProgress; ++round) {
    out.rounds = round + 1;
    relax_folded_regions(pose, context, fold_limits);
    bool progress = keep_if_better();
    if (pose.new_face_count() == 0) break;

    std::vector<char> pushed;
    // The reference's tree serves every round: built at the first push, when a round gets that far.
    if (!reference_tree) reference_tree.emplace(context.reference, faces);
    const Eigen::MatrixX3d push =
        contact_pushes(pose.pose(), context.reference, *reference_tree, faces, pose.new_faces(), pose.pairs(),
                       neighbours, faces_of_vertex, kClearance * mean_edge, pushed);
    std::vector<char> following = within_rings(pushed, neighbours, kFollowingRings);
    for (size_t v = 0; v < following.size(); ++v) {
      if (pushed[v] != 0) following[v] = 0;
    }
    std::optional<Eigen::MatrixX3d> moved =
        as_rigid_as_possible(rest, pose.pose(), faces, following, pushed, pose.pose() + push, neighbours);
    if (!moved) break;
    pose.move_to(*moved);
    progress = keep_if_better() || progress;
    stale_rounds = progress ? 0 : stale_rounds + 1;
  }
  return out;
}

std::pair<std::unique_ptr<RepairStage>, std::unique_ptr<RepairStage>> make_contact_separation_stages() {
  auto cache = std::make_shared<SeparationCache>();
  return {std::make_unique<ContactSeparationStage>(cache, true), std::make_unique<ContactSeparationStage>(cache, false)};
}
std::unique_ptr<RepairStage> make_contact_push_stage() { return std::make_unique<ContactPushStage>(); }

}  // namespace posekit::detail
