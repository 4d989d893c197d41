// posekit's own test shape bent at its joint, built once per process for each size and angle: the
// rest pose is pose 0, the bent one pose 1.
#pragma once

#include <posekit/demo_shape.hpp>

#include <map>
#include <utility>

namespace posekit::testing {

/// The demo arm with `ring_segments` around and one pose bent by `degrees`.
inline const PoseSet& bent_arm(int ring_segments, double degrees) {
  static std::map<std::pair<int, double>, PoseSet> arms;
  const auto key = std::make_pair(ring_segments, degrees);
  auto found = arms.find(key);
  if (found == arms.end()) {
    DemoArmOptions options;
    options.ring_segments = ring_segments;
    options.bend_angles_degrees = {degrees};
    found = arms.emplace(key, make_demo_arm(options)).first;
  }
  return found->second;
}

}  // namespace posekit::testing
