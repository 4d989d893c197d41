#include "correct/local_correction.hpp"

#include "correct/vertex_regions.hpp"

#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/submesh.hpp>
#include <posekit/topology.hpp>

#include <algorithm>
#include <utility>

namespace posekit::detail {
namespace {

// Margins of the two passes: the region must hold the whole entangled part, its surroundings
// and room to blend.
constexpr int kMarginRings[] = {4, 8, 16};

// Rounds of the passes at most.
constexpr int kRounds = 3;

// Beyond this fraction of the vertices a region is the pose again, with the pose's problems (and
// its cost); up to it, a region on its own still misses the parts the whole pose's key frames pass
// it through (lion-07: 806 new faces left with a fifth, 271 with half).
constexpr double kLargestRegionFraction = 0.5;

// A region of fewer faces gives the field too little to fit.
constexpr int kFewestFaces = 16;

// The connected sets joined wherever a face of one intersects a face of another: both sides of an
// intersection belong to one problem (a tail and the leg it went through). Largest first.
std::vector<std::vector<int>> linked_regions(const std::vector<std::vector<int>>& sets, const Eigen::MatrixX3d& pose,
                                             const Eigen::MatrixX3i& faces) {
  std::vector<int> set_of(static_cast<size_t>(pose.rows()), -1);
  for (size_t k = 0; k < sets.size(); ++k) {
    for (int v : sets[k]) set_of[static_cast<size_t>(v)] = static_cast<int>(k);
  }
  std::vector<int> parent(sets.size());
  for (size_t k = 0; k < parent.size(); ++k) parent[k] = static_cast<int>(k);
  const auto root = [&](int k) {
    while (parent[static_cast<size_t>(k)] != k) k = parent[static_cast<size_t>(k)] = parent[static_cast<size_t>(parent[static_cast<size_t>(k)])];
    return k;
  };
  for (const auto& [f, g] : self_intersecting_face_pairs(pose, faces)) {
    const int a = set_of[static_cast<size_t>(faces(f, 0))];
    const int b = set_of[static_cast<size_t>(faces(g, 0))];
    if (a >= 0 && b >= 0) parent[static_cast<size_t>(root(a))] = root(b);
  }
  std::vector<std::vector<int>> regions(sets.size());
  for (size_t k = 0; k < sets.size(); ++k) {
    std::vector<int>& region = regions[static_cast<size_t>(root(static_cast<int>(k)))];
    region.insert(region.end(), sets[k].begin(), sets[k].end());
  }
  regions.erase(std::remove_if(regions.begin(), regions.end(), [](const auto& r) { return r.empty(); }), regions.end());
  std::stable_sort(regions.begin(), regions.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return regions;
}

Eigen::MatrixX3d rows_of(const Eigen::MatrixX3d& pose, const std::vector<int>& vertices) {
  Eigen::MatrixX3d rows(static_cast<Eigen::Index>(vertices.size()), 3);
  for (size_t i = 0; i < vertices.size(); ++i) rows.row(static_cast<Eigen::Index>(i)) = pose.row(vertices[i]);
  return rows;
}

}  // namespace

LocalCorrectionResult correct_regions_locally(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                              const Eigen::MatrixX3i& faces,
                                              const std::vector<int>& reference_intersecting, Device& device,
                                              const CorrectionOptions& options) {
  const int vertex_count = static_cast<int>(result.rows());
  const auto new_faces = [&](const Eigen::MatrixX3d& pose) {
    return new_intersecting_faces(self_intersecting_faces(pose, faces), reference_intersecting);
  };
  LocalCorrectionResult out;
  std::vector<int> current = new_faces(result);
  out.new_faces_before = static_cast<int>(current.size());
  const AdjacencyLists neighbours = vertex_neighbours(faces, vertex_count);
  std::vector<char> changed(static_cast<size_t>(vertex_count), 0);

  CorrectionOptions local = options;
  local.local_correction = false;
  local.intermediate_pose = false;
  // The whole pose's separation runs after this stage; inside each region it freed lion-04 sooner
  // (8 s in all against 26, 2.9e-4 of the diagonal off the target against 7.9e-4) but cost lion-07
  // and cat-07 three and four times the stage's time (45 s against 14, 149 s against 39).
  local.contact_separation = false;
  local.excluded_vertices.clear();

  // A correction can uncover or shift a residue, so the passes repeat while they help.
  for (int round = 0; round < kRounds; ++round) {
    const int regions_before = out.regions;
    for (const int margin : kMarginRings) {
      if (current.empty()) break;
      const std::vector<char> near =
          within_rings(face_vertices(current, faces, static_cast<size_t>(vertex_count)), neighbours, margin);

      for (const std::vector<int>& region : linked_regions(connected_sets(near, neighbours), result, faces)) {
        if (current.empty()) break;
        if (static_cast<double>(region.size()) > kLargestRegionFraction * vertex_count) continue;
        std::vector<char> inside(static_cast<size_t>(vertex_count), 0);
        for (int v : region) inside[static_cast<size_t>(v)] = 1;
        if (!touches(inside, current, faces)) continue;  // an earlier region's correction freed this one
        std::vector<int> sub_vertices;
        const Mesh sub = submesh(reference, faces, faces_within(inside, faces), &sub_vertices);
        if (sub.faces.rows() < kFewestFaces) continue;

        Eigen::MatrixX3d corrected;
        try {
          corrected = correct_pose(sub.vertices, rows_of(result, sub_vertices), sub.faces, device, local);
        } catch (const DeviceError&) {
          throw;
        } catch (const Error&) {
          continue;  // a region the pipeline cannot take on its own (a degenerate field, say)
        }
        // Blended in from the region's rim, which keeps its place, so the seam stays closed.
        std::vector<char> outside(static_cast<size_t>(vertex_count), 0);
        for (int v = 0; v < vertex_count; ++v) outside[static_cast<size_t>(v)] = inside[static_cast<size_t>(v)] == 0;
        const std::vector<int> depth = ring_distances(outside, neighbours, options.blend_rings + 1);
        Eigen::MatrixX3d candidate = result;
        std::vector<int> moved;
        for (size_t i = 0; i < sub_vertices.size(); ++i) {
          const int v = sub_vertices[i];
          const int d = depth[static_cast<size_t>(v)];
          const double weight =
              d < 0 ? 1.0 : std::min(1.0, static_cast<double>(d - 1) / static_cast<double>(options.blend_rings + 1));
          if (weight <= 0.0) continue;
          candidate.row(v) += weight * (corrected.row(static_cast<Eigen::Index>(i)) - result.row(v));
          moved.push_back(v);
        }
        std::vector<int> remaining = new_faces(candidate);
        if (remaining.size() >= current.size()) continue;
        result = std::move(candidate);
        current = std::move(remaining);
        ++out.regions;
        for (int v : moved) changed[static_cast<size_t>(v)] = 1;
      }
    }
    if (out.regions == regions_before || current.empty()) break;
  }
  out.new_faces_after = static_cast<int>(current.size());
  out.vertices = static_cast<int>(std::count(changed.begin(), changed.end(), 1));
  return out;
}

}  // namespace posekit::detail
