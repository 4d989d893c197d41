#include <posekit/error.hpp>
#include <posekit/feature_correspondence.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <string>

namespace posekit {

std::vector<std::vector<int>> permissible_assignments(const std::vector<int>& vertices,
                                                      const std::vector<std::string>& groups, size_t limit) {
  if (vertices.size() != groups.size()) {
    throw ArgumentError("permissible_assignments: " + std::to_string(vertices.size()) + " vertices but " +
                        std::to_string(groups.size()) + " group labels");
  }
  std::map<std::string, std::vector<size_t>> members;
  for (size_t i = 0; i < groups.size(); ++i) {
    if (!groups[i].empty()) members[groups[i]].push_back(i);
  }
  double count = 1.0;
  for (const auto& [name, positions] : members) {
    for (size_t f = 2; f <= positions.size(); ++f) count *= static_cast<double>(f);
  }
  if (count > static_cast<double>(limit)) {
    throw ArgumentError("the feature groups allow " + std::to_string(static_cast<long long>(count)) +
                        " assignments, more than the limit of " + std::to_string(limit) + "; use smaller groups");
  }
  std::vector<std::vector<int>> assignments{vertices};
  for (const auto& [name, positions] : members) {
    std::vector<int> own;
    for (size_t p : positions) own.push_back(vertices[p]);
    // Permutations in lexicographic order of the group's positions, starting from the given one.
    std::vector<size_t> order(own.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::vector<std::vector<int>> expanded;
    for (const std::vector<int>& base : assignments) {
      std::vector<size_t> permutation = order;
      do {
        std::vector<int> next = base;
        for (size_t i = 0; i < positions.size(); ++i) next[positions[i]] = own[permutation[i]];
        expanded.push_back(std::move(next));
      } while (std::next_permutation(permutation.begin(), permutation.end()));
    }
    assignments = std::move(expanded);
  }
  return assignments;
}

CorrespondenceChoice choose_correspondence(BlendedDeformer& deformer,
                                           const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                           const std::vector<std::vector<int>>& assignments, double weight) {
  if (assignments.empty()) throw ArgumentError("choose_correspondence: no assignment to choose from");
  for (const std::vector<int>& assignment : assignments) {
    if (static_cast<Eigen::Index>(assignment.size()) != positions.rows()) {
      throw ArgumentError("choose_correspondence: an assignment has " + std::to_string(assignment.size()) +
                          " vertices for " + std::to_string(positions.rows()) + " positions");
    }
  }
  const auto constrain = [&](const std::vector<int>& assignment) {
    std::vector<LinearConstraint> constraints;
    for (int v : assignment) constraints.push_back(LinearConstraint::vertex(v, weight));
    deformer.set_constraints(constraints);
  };
  CorrespondenceChoice choice;
  choice.energies.assign(assignments.size(), std::numeric_limits<double>::infinity());
  constrain(assignments.front());
  std::vector<int> current = assignments.front();
  for (size_t a = 0; a < assignments.size(); ++a) {
    for (size_t r = 0; r < current.size(); ++r) {
      if (assignments[a][r] == current[r]) continue;
      deformer.replace_constraint(static_cast<int>(r), LinearConstraint::vertex(assignments[a][r], weight));
      current[r] = assignments[a][r];
    }
    BlendResult result = deformer.deform(positions);
    choice.energies[a] = result.energy;
    if (a == 0 || result.energy < choice.result.energy) {
      choice.assignment = static_cast<int>(a);
      choice.result = std::move(result);
    }
  }
  choice.vertices = assignments[static_cast<size_t>(choice.assignment)];
  // Leave the deformer with a fresh factorization of the chosen constraints.
  constrain(choice.vertices);
  return choice;
}

}  // namespace posekit
