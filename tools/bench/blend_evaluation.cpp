// The evaluation of example-based deformation on the shared pose sets, as tables:
//  1. leave-one-out: every pose reconstructed from the others as examples with (a) all its vertices,
//     (b) 20 and (c) 10 well-spread vertices as constraints; maximal and mean distortion (vertex error
//     over the square root of the pose's area) and the time per deformation;
//  2. scale: the same with the 20 constraints taken from the pose scaled by 1.5, the recovered scale
//     and its ratio to the scale at the pose's own size; and from an example scaled by 1.5;
//  3. partial registration: each pose with 40 % of its surface removed (grown from three seeds far
//     from the features, never within a geodesic distance of 15 % of the square root of the area of
//     a feature, measured along edges) and 8 known feature points; the completed mesh's distortion and the fraction of scan points whose
//     correspondence lies within 5 % of the square root of the area of their true position.
//
// Constraint vertices are spread over the set's first pose (farthest points; over the held-out pose
// with --spread-on-pose); every table is made for
// each dictionary asked for (`--dictionary lbo|skeleton|auto|both`), side by side, and a last table
// lists each pose's 95th-percentile vertex error over the bounding-box diagonal with 20 points.
//
// posekit_blend_evaluation [--data DIR] [--sets a,b,...] [--poses N] [--skip-registration]
//                          [--feature-rings N] [--choice-after-solve] [--average-iterations N]
//                          [--minimal-iterations N] [--smoothness-weight S] [--dictionary D]
//                          [--bones N] [--skeleton-iterations A,M] [--spread-on-pose] [--verbose]
#include <posekit/blended_deformation.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/partial_registration.hpp>
#include <posekit/submesh.hpp>
#include <posekit/topology.hpp>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "blend/edge_distances.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <queue>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace posekit {
namespace {

struct Settings {
  std::filesystem::path data = POSEKIT_BENCH_DATA_DIR;
  std::vector<std::string> sets = {"horse-poses", "cat-poses", "lion-poses", "elephant-poses"};
  int poses = 1000;
  bool registration = true;
  int feature_rings = ScanFitOptions{}.feature_rings;
  bool verbose = false;
  BlendOptions blend;
  std::vector<DictionaryChoice> dictionaries = {DictionaryChoice::lbo};
  bool spread_on_pose = false;  // spread the constraint vertices over the held-out pose, not the set's first
};

std::vector<int> spread_vertices(const Eigen::MatrixX3d& vertices, int count, std::vector<int> chosen = {}) {
  return farthest_point_samples(vertices, count, std::move(chosen));
}

struct Distortion {
  double max = 0.0;
  double mean = 0.0;
  double p95_of_diagonal = 0.0;  // 95th percentile of the vertex error over the bounding-box diagonal
};

// The baseline: the example that, rigidly placed on the constrained vertices (Kabsch), meets them
// best, and its distortion.
Distortion nearest_example(const PoseSet& examples, const std::vector<int>& vertices, const Eigen::MatrixX3d& truth,
                           const Eigen::MatrixX3i& faces);

Distortion distortion(const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& truth, const Eigen::MatrixX3i& faces) {
  const Eigen::VectorXd distance = (result - truth).rowwise().norm();
  const Eigen::VectorXd error = distance / std::sqrt(face_areas(truth, faces).sum());
  std::vector<double> sorted(distance.data(), distance.data() + distance.size());
  const size_t rank = static_cast<size_t>(0.95 * static_cast<double>(sorted.size() - 1) + 0.5);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank), sorted.end());
  return {error.maxCoeff(), error.mean(), sorted[rank] / bounding_box_diagonal(truth)};
}

Distortion nearest_example(const PoseSet& examples, const std::vector<int>& vertices, const Eigen::MatrixX3d& truth,
                           const Eigen::MatrixX3i& faces) {
  double best_residual = std::numeric_limits<double>::infinity();
  Distortion best;
  for (int k = 0; k < examples.pose_count(); ++k) {
    Eigen::MatrixX3d a(static_cast<Eigen::Index>(vertices.size()), 3), b(a.rows(), 3);
    for (size_t r = 0; r < vertices.size(); ++r) {
      a.row(static_cast<Eigen::Index>(r)) = examples.pose(k).row(vertices[r]);
      b.row(static_cast<Eigen::Index>(r)) = truth.row(vertices[r]);
    }
    const Eigen::RowVector3d ca = a.colwise().mean(), cb = b.colwise().mean();
    const Eigen::Matrix3d covariance = (b.rowwise() - cb).transpose() * (a.rowwise() - ca);
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d u = svd.matrixU();
    if ((u * svd.matrixV().transpose()).determinant() < 0.0) u.col(2) *= -1.0;
    const Eigen::Matrix3d rotation = u * svd.matrixV().transpose();
    const Eigen::MatrixX3d placed = ((examples.pose(k).rowwise() - ca) * rotation.transpose()).rowwise() + cb;
    double residual = 0.0;
    for (int v : vertices) residual += (placed.row(v) - truth.row(v)).squaredNorm();
    if (residual < best_residual) {
      best_residual = residual;
      best = distortion(placed, truth, faces);
    }
  }
  return best;
}

// Summary of one table cell over the poses.
struct Cell {
  std::vector<double> max, mean, p95, seconds, extra;
  void add(const Distortion& d, double s, double e = 0.0) {
    max.push_back(d.max);
    mean.push_back(d.mean);
    p95.push_back(d.p95_of_diagonal);
    seconds.push_back(s);
    extra.push_back(e);
  }
  static double average(const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  }
  static double largest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
  static double smallest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }
  static double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  }
};

PoseSet read_set(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  // A set's reference pose, when it has one, comes first.
  std::stable_partition(files.begin(), files.end(),
                        [](const std::filesystem::path& p) { return p.filename().string().find("reference") != std::string::npos; });
  return read_pose_set(files);
}

// Faces removed from `pose`: grown breadth-first by centroid distance from `seeds` until `fraction`
// of the area is gone, never touching a face with a vertex within `radius` of a feature.
std::vector<char> removed_faces(const Eigen::MatrixX3d& pose, const Eigen::MatrixX3i& faces, const std::vector<int>& features,
                                const std::vector<int>& seeds, double radius, double fraction) {
  const Eigen::VectorXd areas = face_areas(pose, faces);
  const double total = areas.sum();
  const int face_count = static_cast<int>(faces.rows());
  Eigen::MatrixX3d centroids(face_count, 3);
  // Geodesic discs (shortest paths along edges) around the features stay.
  std::vector<char> near_feature(static_cast<size_t>(pose.rows()), 0);
  const AdjacencyLists ring = vertex_neighbours(faces, static_cast<int>(pose.rows()));
  for (int v : features) {
    const Eigen::VectorXd d = detail::edge_distances(pose, ring, v, radius);
    for (Eigen::Index u = 0; u < d.size(); ++u) near_feature[static_cast<size_t>(u)] |= d(u) <= radius;
  }
  std::vector<char> protect(static_cast<size_t>(face_count), 0);
  for (int f = 0; f < face_count; ++f) {
    centroids.row(f) = (pose.row(faces(f, 0)) + pose.row(faces(f, 1)) + pose.row(faces(f, 2))) / 3;
    for (int c = 0; c < 3; ++c) protect[static_cast<size_t>(f)] |= near_feature[static_cast<size_t>(faces(f, c))];
  }
  const EdgeMap edges = edge_map(faces);
  const AdjacencyLists faces_of_edge = edge_faces(edges);
  const AdjacencyLists faces_of_vertex = vertex_faces(faces, static_cast<int>(pose.rows()));
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  std::vector<double> best(static_cast<size_t>(face_count), std::numeric_limits<double>::infinity());
  for (int seed : seeds) {
    for (int f : faces_of_vertex[seed]) {
      if (protect[static_cast<size_t>(f)]) continue;
      best[static_cast<size_t>(f)] = 0.0;
      queue.push({0.0, f});
    }
  }
  std::vector<char> removed(static_cast<size_t>(face_count), 0);
  double removed_area = 0.0;
  while (removed_area < fraction * total) {
    if (queue.empty()) {
      // The grown regions are walled in by protected faces: start another one at the free face
      // farthest from the features.
      int farthest = -1;
      double largest = -1.0;
      for (int f = 0; f < face_count; ++f) {
        if (removed[static_cast<size_t>(f)] || protect[static_cast<size_t>(f)]) continue;
        double nearest = std::numeric_limits<double>::infinity();
        for (int v : features) nearest = std::min(nearest, (centroids.row(f) - pose.row(v)).norm());
        if (nearest > largest) {
          largest = nearest;
          farthest = f;
        }
      }
      if (farthest < 0) break;
      best[static_cast<size_t>(farthest)] = 0.0;
      queue.push({0.0, farthest});
    }
    const auto [d, f] = queue.top();
    queue.pop();
    if (removed[static_cast<size_t>(f)] || d > best[static_cast<size_t>(f)]) continue;
    removed[static_cast<size_t>(f)] = 1;
    removed_area += areas(f);
    for (int c = 0; c < 3; ++c) {
      for (int g : faces_of_edge[edges.face_edges(f, c)]) {
        if (removed[static_cast<size_t>(g)] || protect[static_cast<size_t>(g)]) continue;
        const double next = d + (centroids.row(f) - centroids.row(g)).norm();
        if (next < best[static_cast<size_t>(g)]) {
          best[static_cast<size_t>(g)] = next;
          queue.push({next, g});
        }
      }
    }
  }
  return removed;
}

Mesh kept_part(const Eigen::MatrixX3d& pose, const Eigen::MatrixX3i& faces, const std::vector<char>& removed,
               std::vector<int>& original) {
  std::vector<char> kept(removed.size());
  for (size_t f = 0; f < removed.size(); ++f) kept[f] = removed[f] == 0;
  return submesh(pose, faces, kept, &original);
}

struct SetResults {
  std::string name;
  std::string dictionary;
  std::vector<std::string> pose_names;
  int bones = 0;
  double skinning_error = 0.0;
  int poses = 0;
  int vertices = 0;
  Cell cases[3];
  Cell baseline[3];
  Cell scaled;          // the held-out pose's 20 constraints, 1.5 times larger; extra: the scale
  Cell scale_ratio;     // extra: that scale over the scale from the constraints at their own size
  Cell scaled_example;  // an example's own 20 constraints, 1.5 times larger; extra: the scale
  Cell scaled_size;     // extra: sqrt(area of the result / area of the pose 1.5 times larger), held-out
  Cell example_size;    // the same for the example
  Cell initial, completed;
  std::vector<double> correct_fraction, removed_fraction, registration_seconds;
  double setup_seconds = 0.0;
  int atoms = 0;
  int clusters = 0;
};

SetResults evaluate(const Settings& settings, const std::string& name, DictionaryChoice dictionary) {
  SetResults out;
  out.name = name;
  out.dictionary = dictionary_choice_name(dictionary);
  const PoseSet all = read_set(settings.data / name);
  const Eigen::MatrixX3i& faces = all.faces();
  out.vertices = all.vertex_count();
  std::vector<int> every(static_cast<size_t>(all.vertex_count()));
  for (size_t v = 0; v < every.size(); ++v) every[v] = static_cast<int>(v);
  const int poses = std::min(all.pose_count(), settings.poses);
  BlendOptions blend = settings.blend;
  blend.dictionary = dictionary;
  for (int h = 0; h < poses; ++h) {
    PoseSet examples(faces);
    for (int k = 0; k < all.pose_count(); ++k) {
      if (k != h) examples.add_pose(all.pose(k), all.pose_name(k));
    }
    BlendedDeformer deformer(examples, blend);
    out.setup_seconds += deformer.setup_report().seconds.total;
    out.atoms = deformer.setup_report().atoms;
    out.clusters = deformer.setup_report().clusters;
    out.bones = deformer.setup_report().bones;
    out.skinning_error = std::max(out.skinning_error, deformer.setup_report().skinning_error);
    out.pose_names.push_back(all.pose_name(h));
    const Eigen::MatrixX3d& truth = all.pose(h);
    const std::vector<int> c20 = spread_vertices(settings.spread_on_pose ? truth : all.pose(0), 20);
    const std::vector<int> c10(c20.begin(), c20.begin() + 10);
    const std::vector<int>* sets[3] = {&every, &c20, &c10};
    for (int c = 0; c < 3; ++c) {
      std::vector<LinearConstraint> constraints;
      Eigen::MatrixX3d targets(static_cast<Eigen::Index>(sets[c]->size()), 3);
      for (size_t r = 0; r < sets[c]->size(); ++r) {
        constraints.push_back(LinearConstraint::vertex((*sets[c])[r]));
        targets.row(static_cast<Eigen::Index>(r)) = truth.row((*sets[c])[r]);
      }
      deformer.set_constraints(constraints);
      const BlendResult result = deformer.deform(targets);
      const Distortion d = distortion(result.vertices, truth, faces);
      out.cases[c].add(d, result.seconds);
      if (c > 0) out.baseline[c].add(nearest_example(examples, *sets[c], truth, faces), 0.0);
      if (settings.verbose) {
        std::printf("  %s %s case %c: max %.2f %% mean %.3f %% p95 %.2f %% of the diagonal, scale %.3f %.2f ms\n",
                    out.dictionary.c_str(), all.pose_name(h).c_str(), "abc"[c], 100 * d.max, 100 * d.mean,
                    100 * d.p95_of_diagonal, result.scale, 1e3 * result.seconds);
      }
      if (c == 1) {
        const Eigen::RowVector3d center = truth.colwise().mean();
        const Eigen::MatrixX3d bigger = ((truth.rowwise() - center) * 1.5).rowwise() + center;
        for (size_t r = 0; r < c20.size(); ++r) targets.row(static_cast<Eigen::Index>(r)) = bigger.row(c20[r]);
        const BlendResult scaled = deformer.deform(targets);
        out.scaled.add(distortion(scaled.vertices, bigger, faces), scaled.seconds, scaled.scale);
        out.scale_ratio.add(Distortion{}, 0.0, scaled.scale / result.scale);
        // A pose inside the examples' span, where the scale to find is exactly 1.5.
        const Eigen::MatrixX3d& example = examples.pose(std::min(1, examples.pose_count() - 1));
        const Eigen::RowVector3d example_center = example.colwise().mean();
        const Eigen::MatrixX3d bigger_example = ((example.rowwise() - example_center) * 1.5).rowwise() + example_center;
        for (size_t r = 0; r < c20.size(); ++r) targets.row(static_cast<Eigen::Index>(r)) = bigger_example.row(c20[r]);
        const BlendResult from_example = deformer.deform(targets);
        out.scaled_example.add(distortion(from_example.vertices, bigger_example, faces), from_example.seconds,
                               from_example.scale);
        const auto size_ratio = [&](const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& truth_pose) {
          return std::sqrt(face_areas(result, faces).sum() / face_areas(truth_pose, faces).sum());
        };
        out.scaled_size.add(Distortion{}, 0.0, size_ratio(scaled.vertices, bigger));
        out.example_size.add(Distortion{}, 0.0, size_ratio(from_example.vertices, bigger_example));
      }
    }
    if (settings.registration) {
      const double length = std::sqrt(face_areas(truth, faces).sum());
      const std::vector<int> features = spread_vertices(truth, 8);
      std::vector<int> seeds = spread_vertices(truth, 11, features);
      seeds.erase(seeds.begin(), seeds.begin() + 8);
      const std::vector<char> removed = removed_faces(truth, faces, features, seeds, 0.15 * length, 0.4);
      std::vector<int> original;
      const Mesh scan = kept_part(truth, faces, removed, original);
      const Eigen::VectorXd areas = face_areas(truth, faces);
      double gone = 0.0;
      for (Eigen::Index f = 0; f < faces.rows(); ++f) gone += removed[static_cast<size_t>(f)] ? areas(f) : 0.0;
      Eigen::MatrixX3d positions(8, 3);
      for (int r = 0; r < 8; ++r) positions.row(r) = truth.row(features[static_cast<size_t>(r)]);
      ScanFitOptions fit;
      fit.feature_rings = settings.feature_rings;
      const ScanRegistration reg = register_partial_scan(deformer, scan, features, positions, fit);
      int good = 0;
      for (Eigen::Index i = 0; i < scan.vertices.rows(); ++i) {
        good += (truth.row(reg.correspondence(i)) - truth.row(original[static_cast<size_t>(i)])).norm() < 0.05 * length;
      }
      out.initial.add(distortion(reg.initial.vertices, truth, faces), reg.initial.seconds);
      out.completed.add(distortion(reg.deformation.vertices, truth, faces), reg.seconds);
      out.correct_fraction.push_back(static_cast<double>(good) / static_cast<double>(scan.vertices.rows()));
      out.removed_fraction.push_back(gone / areas.sum());
      if (settings.verbose) {
        for (const ScanFitIteration& it : reg.iterations) {
          std::printf("    icp: %d matches, median distance %.4f, energy %.4g\n", it.matches, it.median_distance / length,
                      it.energy);
        }
        std::printf("  %s registration: removed %.1f %%, %d disc centroids, initial max %.2f %%, completed max %.2f %% "
                    "mean %.3f %%, %.1f %% correct, %.2f s\n",
                    all.pose_name(h).c_str(), 100 * out.removed_fraction.back(), reg.feature_discs, 100 * out.initial.max.back(),
                    100 * out.completed.max.back(), 100 * out.completed.mean.back(), 100 * out.correct_fraction.back(),
                    reg.seconds);
      }
    }
    ++out.poses;
    std::fflush(stdout);
  }
  return out;
}

}  // namespace
}  // namespace posekit

int main(int argc, char** argv) {
  using namespace posekit;
  Settings settings;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << arg << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--data") {
      settings.data = value();
    } else if (arg == "--sets") {
      settings.sets.clear();
      std::stringstream list(value());
      std::string item;
      while (std::getline(list, item, ',')) settings.sets.push_back(item);
    } else if (arg == "--poses") {
      settings.poses = std::atoi(value().c_str());
    } else if (arg == "--feature-rings") {
      settings.feature_rings = std::atoi(value().c_str());
    } else if (arg == "--skip-registration") {
      settings.registration = false;
    } else if (arg == "--verbose") {
      settings.verbose = true;
    } else if (arg == "--choice-after-solve") {
      settings.blend.example_choice_after_solve = true;
    } else if (arg == "--smoothness-weight") {
      settings.blend.smoothness_weight = std::atof(value().c_str());
    } else if (arg == "--average-iterations") {
      settings.blend.average_iterations = std::atoi(value().c_str());
    } else if (arg == "--minimal-iterations") {
      settings.blend.minimal_iterations = std::atoi(value().c_str());
    } else if (arg == "--spread-on-pose") {
      settings.spread_on_pose = true;
    } else if (arg == "--bones") {
      settings.blend.skinning.bones = std::atoi(value().c_str());
    } else if (arg == "--skeleton-iterations") {
      const std::string counts = value();
      settings.blend.skeleton_average_iterations = std::atoi(counts.c_str());
      settings.blend.skeleton_minimal_iterations = std::atoi(counts.substr(counts.find(',') + 1).c_str());
    } else if (arg == "--dictionary") {
      const std::string choice = value();
      if (choice == "lbo") {
        settings.dictionaries = {DictionaryChoice::lbo};
      } else if (choice == "skeleton") {
        settings.dictionaries = {DictionaryChoice::skeleton};
      } else if (choice == "auto") {
        settings.dictionaries = {DictionaryChoice::automatic};
      } else if (choice == "both") {
        settings.dictionaries = {DictionaryChoice::lbo, DictionaryChoice::skeleton};
      } else {
        std::cerr << "--dictionary must be lbo, skeleton, auto or both\n";
        return 2;
      }
    } else {
      std::cerr << "usage: posekit_blend_evaluation [--data DIR] [--sets a,b,...] [--poses N] [--skip-registration] "
                   "[--feature-rings N] [--choice-after-solve] [--average-iterations N] [--minimal-iterations N] [--smoothness-weight S] "
                   "[--dictionary lbo|skeleton|auto|both] [--bones N] [--skeleton-iterations AVERAGE,MINIMAL] [--spread-on-pose] [--verbose]\n";
      return 2;
    }
  }
  std::vector<SetResults> results;
  for (const std::string& name : settings.sets) {
    if (!std::filesystem::exists(settings.data / name)) {
      std::printf("%s: not found under %s, skipped\n", name.c_str(), settings.data.string().c_str());
      continue;
    }
    for (DictionaryChoice dictionary : settings.dictionaries) {
      if (settings.verbose) std::printf("%s, %s dictionary\n", name.c_str(), dictionary_choice_name(dictionary));
      results.push_back(evaluate(settings, name, dictionary));
    }
  }
  std::printf("\nLeave-one-out (distortion = vertex error / sqrt(area); max: mean over poses of the largest, worst: "
              "largest over poses)\n");
  std::printf("| set | dictionary | vertices | poses | atoms | clusters | case | max %% | worst max %% | mean %% | p95 %% of "
              "the diagonal: mean / worst | ms per deformation (median) | nearest example rigidly placed: max %% / mean %% |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const char* labels[3] = {"(a) all vertices", "(b) 20 vertices", "(c) 10 vertices"};
  for (const SetResults& r : results) {
    for (int c = 0; c < 3; ++c) {
      const Cell& cell = r.cases[c];
      std::printf("| %s | %s | %d | %d | %d | %d | %s | %.2f | %.2f | %.3f | %.2f / %.2f | %.2f | ", r.name.c_str(),
                  r.dictionary.c_str(), r.vertices, r.poses, r.atoms, r.clusters, labels[c], 100 * Cell::average(cell.max),
                  100 * Cell::largest(cell.max), 100 * Cell::average(cell.mean), 100 * Cell::average(cell.p95),
                  100 * Cell::largest(cell.p95), 1e3 * Cell::median(cell.seconds));
      if (c == 0) {
        std::printf("- |\n");
      } else {
        std::printf("%.2f / %.3f |\n", 100 * Cell::average(r.baseline[c].max), 100 * Cell::average(r.baseline[c].mean));
      }
    }
  }
  std::printf("\nScale: 20 constraints scaled by 1.5, from the held-out pose (its scale against the examples is "
              "not exactly 1 at its own size, hence the ratio) and from an example (scale exactly 1.5); mean, min, max\n");
  std::printf("| set | dictionary | held-out x1.5: scale | max %% / mean %% | scale x1.5 / scale x1 | size of the result / size "
              "of the pose | example x1.5: scale | max %% / mean %% | size of the result / size of the pose "
              "|\n|---|---|---|---|---|---|---|---|---|\n");
  const auto triple = [](const std::vector<double>& v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4f, %.4f, %.4f", Cell::average(v), Cell::smallest(v), Cell::largest(v));
    return std::string(text);
  };
  for (const SetResults& r : results) {
    std::printf("| %s | %s | %s | %.2f / %.3f | %s | %s | %s | %.2f / %.3f | %s |\n", r.name.c_str(), r.dictionary.c_str(),
                triple(r.scaled.extra).c_str(), 100 * Cell::average(r.scaled.max), 100 * Cell::average(r.scaled.mean),
                triple(r.scale_ratio.extra).c_str(), triple(r.scaled_size.extra).c_str(),
                triple(r.scaled_example.extra).c_str(), 100 * Cell::average(r.scaled_example.max),
                100 * Cell::average(r.scaled_example.mean), triple(r.example_size.extra).c_str());
  }
  if (settings.registration) {
    std::printf("\nPartial registration: 8 feature points, surface removed as listed; correspondences within 5 %% of "
                "sqrt(area)\n");
    std::printf("| set | dictionary | removed %% | features only: max %% / mean %% | completed: max %% / mean %% | correct "
                "correspondences %% (mean, min) | s per registration |\n|---|---|---|---|---|---|---|\n");
    for (const SetResults& r : results) {
      std::printf("| %s | %s | %.1f | %.2f / %.3f | %.2f / %.3f | %.1f, %.1f | %.2f |\n", r.name.c_str(), r.dictionary.c_str(),
                  100 * Cell::average(r.removed_fraction), 100 * Cell::average(r.initial.max),
                  100 * Cell::average(r.initial.mean), 100 * Cell::average(r.completed.max),
                  100 * Cell::average(r.completed.mean), 100 * Cell::average(r.correct_fraction),
                  100 * Cell::smallest(r.correct_fraction), Cell::average(r.completed.seconds));
    }
  }
  std::printf("\nEach pose from 20 spread points: 95th-percentile vertex error, %% of the bounding-box diagonal\n| set | pose |");
  for (const SetResults& r : results) {
    if (r.name == results.front().name) std::printf(" %s |", r.dictionary.c_str());
  }
  std::printf("\n");
  for (size_t first = 0; first < results.size();) {
    size_t last = first;
    while (last < results.size() && results[last].name == results[first].name) ++last;
    for (size_t pose = 0; pose < results[first].pose_names.size(); ++pose) {
      std::printf("| %s | %s |", results[first].name.c_str(), results[first].pose_names[pose].c_str());
      for (size_t r = first; r < last; ++r) std::printf(" %.2f |", 100 * results[r].cases[1].p95[pose]);
      std::printf("\n");
    }
    first = last;
  }
  for (const SetResults& r : results) {
    std::printf("%s, %s: precomputation %.2f s per fold on average", r.name.c_str(), r.dictionary.c_str(),
                r.setup_seconds / std::max(1, r.poses));
    if (r.bones > 0) std::printf(", %d bones, skinning RMS error up to %.2f %% of the diagonal", r.bones, 100 * r.skinning_error);
    std::printf("\n");
  }
  return 0;
}
