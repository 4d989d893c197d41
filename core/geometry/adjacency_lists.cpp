#include <posekit/error.hpp>
#include <posekit/topology.hpp>

#include <string>
#include <utility>

namespace posekit {

AdjacencyLists::AdjacencyLists(std::vector<int> offsets, std::vector<int> indices)
    : offsets_(std::move(offsets)), indices_(std::move(indices)) {
  if (offsets_.empty() || offsets_.front() != 0) {
    throw ArgumentError("AdjacencyLists: offsets must start with 0");
  }
  for (size_t i = 1; i < offsets_.size(); ++i) {
    if (offsets_[i] < offsets_[i - 1]) {
      throw ArgumentError("AdjacencyLists: offsets decrease at entry " + std::to_string(i));
    }
  }
  if (static_cast<size_t>(offsets_.back()) != indices_.size()) {
    throw ArgumentError("AdjacencyLists: last offset " + std::to_string(offsets_.back()) +
                        " differs from the index count " + std::to_string(indices_.size()));
  }
}

}  // namespace posekit
