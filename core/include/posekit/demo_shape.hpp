// posekit's own articulated test shape: a capsule "arm" bent at its middle by linear blend skinning.
// Strong bends collapse the inner side of the joint into itself (the classic skinning artefact),
// which gives self-intersecting poses with a clean rest pose, without any external data.
#pragma once

#include <posekit/mesh.hpp>

#include <vector>

namespace posekit {

/// Shape and poses of the demo arm. Lengths are in arbitrary units.
struct DemoArmOptions {
  /// Vertices around each ring (>= 8, a multiple of 4). Rings are spaced one segment apart along the
  /// profile and every other ring is turned by half a segment, so triangles on the cylinder are close
  /// to equilateral (those of the caps narrow towards the poles). 48 gives 4,034 vertices and 8,064
  /// faces with the default lengths.
  int ring_segments = 48;
  /// Radius of the tube and of its hemispherical caps (> 0).
  double radius = 0.5;
  /// Length of the cylindrical part along +x, from x = 0 to x = cylinder_length (> 0); the joint
  /// sits at its middle.
  double cylinder_length = 4.0;
  /// Width along x over which the skinning weight moves from the first bone to the second, centred on
  /// the joint (> 0, at most cylinder_length).
  double blend_width = 1.0;
  /// Bend angles in degrees (each in [-180, 180]) of the second bone about the +z axis through the joint;
  /// one pose per angle. Positive angles bend the arm towards +y.
  std::vector<double> bend_angles_degrees = {45.0, 90.0, 135.0};
};

/// The demo arm: the straight rest pose first (named "rest"), then one bent pose per entry of
/// options.bend_angles_degrees (named "bend-<angle>"), all on one closed, outward-oriented face list.
/// Deterministic. Throws ArgumentError when an option is out of range.
PoseSet make_demo_arm(const DemoArmOptions& options = {});

}  // namespace posekit
