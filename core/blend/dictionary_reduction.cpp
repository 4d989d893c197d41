#include <posekit/blend_dictionary.hpp>
#include <posekit/error.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace posekit {
namespace {

// Atoms that are (nearly) multiples of each other span the same direction; 1 - |cos| makes them
// coincide whatever their sign and length.
Eigen::MatrixXd atom_distances(const BlendDictionary& dictionary, const Eigen::VectorXd& mass, int sample_vertices) {
  const int vertex_count = dictionary.vertex_count();
  const int samples = std::min(vertex_count, std::max(1, sample_vertices));
  Eigen::MatrixXd sampled(samples, dictionary.atom_count());
  for (int s = 0; s < samples; ++s) {
    const int v = static_cast<int>((static_cast<long long>(s) * vertex_count) / samples);
    const double root_mass = std::sqrt(std::max(mass(v), 0.0));
    for (int p = 0; p < dictionary.atom_count(); ++p) sampled(s, p) = root_mass * dictionary.value(v, p);
  }
  for (int p = 0; p < sampled.cols(); ++p) {
    const double norm = sampled.col(p).norm();
    if (norm > 0.0) sampled.col(p) /= norm;
  }
  Eigen::MatrixXd distance = Eigen::MatrixXd::Ones(sampled.cols(), sampled.cols());
  distance.noalias() -= (sampled.transpose() * sampled).cwiseAbs();
  distance = distance.cwiseMax(0.0);
  distance.diagonal().setZero();
  return distance;
}

}  // namespace

BlendDictionary reduce_dictionary(const BlendDictionary& dictionary, int atom_count, const Eigen::VectorXd& mass,
                                  const std::vector<int>& keep, int sample_vertices) {
  if (atom_count < 1) throw ArgumentError("reduce_dictionary: atom_count is " + std::to_string(atom_count) + "; it must be >= 1");
  if (static_cast<int>(keep.size()) > atom_count) {
    throw ArgumentError("reduce_dictionary: " + std::to_string(keep.size()) + " atoms to keep but only " +
                        std::to_string(atom_count) + " kept in all");
  }
  for (int p : keep) {
    if (p < 0 || p >= dictionary.atom_count()) throw ArgumentError("reduce_dictionary: atom to keep out of range");
  }
  if (mass.size() != dictionary.vertex_count()) {
    throw ArgumentError("reduce_dictionary: " + std::to_string(mass.size()) + " masses for " +
                        std::to_string(dictionary.vertex_count()) + " vertices");
  }
  const int n = dictionary.atom_count();
  if (atom_count >= n) return dictionary;
  const Eigen::MatrixXd distance = atom_distances(dictionary, mass, sample_vertices);

  // Farthest-first start from the atoms to keep, or else the most central atom.
  std::vector<int> medoids;
  std::vector<char> fixed(static_cast<size_t>(atom_count), 0);
  {
    Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, 2.0);
    for (int p : keep) {
      if (std::find(medoids.begin(), medoids.end(), p) != medoids.end()) continue;
      fixed[medoids.size()] = 1;
      medoids.push_back(p);
      nearest = nearest.cwiseMin(distance.col(p));
    }
    if (medoids.empty()) {
      Eigen::Index central = 0;
      distance.colwise().sum().minCoeff(&central);
      medoids.push_back(static_cast<int>(central));
      nearest = distance.col(central);
    }
    while (static_cast<int>(medoids.size()) < atom_count) {
      Eigen::Index farthest = 0;
      nearest.maxCoeff(&farthest);
      medoids.push_back(static_cast<int>(farthest));
      nearest = nearest.cwiseMin(distance.col(farthest));
    }
  }

  // Alternate: assign every atom to its nearest medoid, then move each medoid to the member with the
  // least total distance to the others.
  std::vector<int> assignment(static_cast<size_t>(n), 0);
  for (int iteration = 0; iteration < 100; ++iteration) {
    for (int p = 0; p < n; ++p) {
      double best = std::numeric_limits<double>::infinity();
      for (int c = 0; c < atom_count; ++c) {
        const double d = distance(p, medoids[static_cast<size_t>(c)]);
        if (d < best) {
          best = d;
          assignment[static_cast<size_t>(p)] = c;
        }
      }
    }
    for (int c = 0; c < atom_count; ++c) assignment[static_cast<size_t>(medoids[static_cast<size_t>(c)])] = c;
    // A medoid identical to another one (more atoms asked for than distinct ones exist) is moved to
    // the atom worst represented so far.
    for (int c = 1; c < atom_count; ++c) {
      if (fixed[static_cast<size_t>(c)]) continue;
      for (int b = 0; b < c; ++b) {
        if (distance(medoids[static_cast<size_t>(c)], medoids[static_cast<size_t>(b)]) > 0.0) continue;
        int worst = -1;
        double worst_distance = 0.0;
        for (int p = 0; p < n; ++p) {
          const double d = distance(p, medoids[static_cast<size_t>(assignment[static_cast<size_t>(p)])]);
          if (d > worst_distance) {
            worst_distance = d;
            worst = p;
          }
        }
        if (worst >= 0) {
          medoids[static_cast<size_t>(c)] = worst;
          assignment[static_cast<size_t>(worst)] = c;
        }
        break;
      }
    }
    std::vector<std::vector<int>> members(static_cast<size_t>(atom_count));
    for (int p = 0; p < n; ++p) members[static_cast<size_t>(assignment[static_cast<size_t>(p)])].push_back(p);
    bool moved = false;
    for (int c = 0; c < atom_count; ++c) {
      if (fixed[static_cast<size_t>(c)]) continue;
      const std::vector<int>& cluster = members[static_cast<size_t>(c)];
      int best_member = medoids[static_cast<size_t>(c)];
      double best_cost = std::numeric_limits<double>::infinity();
      for (int candidate : cluster) {
        double cost = 0.0;
        for (int other : cluster) cost += distance(candidate, other);
        // Ties keep the current medoid, so the iteration cannot cycle.
        if (cost < best_cost - 1e-15 || (candidate == medoids[static_cast<size_t>(c)] && cost <= best_cost + 1e-15)) {
          best_cost = cost;
          best_member = candidate;
        }
      }
      if (best_member != medoids[static_cast<size_t>(c)]) {
        medoids[static_cast<size_t>(c)] = best_member;
        moved = true;
      }
    }
    if (!moved) break;
  }
  std::sort(medoids.begin(), medoids.end());
  std::vector<DictionaryAtom> atoms;
  atoms.reserve(medoids.size());
  for (int p : medoids) atoms.push_back(dictionary.atoms()[static_cast<size_t>(p)]);
  return BlendDictionary(dictionary.examples(), dictionary.weights(), std::move(atoms));
}

}  // namespace posekit
