#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Keeps the arm a demo shape: beyond this the vertex count would no longer fit comfortably in memory.
constexpr std::int64_t kMaxVertexCount = 10'000'000;

// One circle of vertices around the x axis.
struct Ring {
  double x;
  double radius;
};

void check_options(const DemoArmOptions& options) {
  if (options.ring_segments < 8 || options.ring_segments % 4 != 0) {
    throw ArgumentError("DemoArmOptions::ring_segments must be a multiple of 4 and at least 8 (got " +
                        std::to_string(options.ring_segments) + ")");
  }
  if (!std::isfinite(options.radius) || options.radius <= 0.0) {
    throw ArgumentError("DemoArmOptions::radius must be positive and finite");
  }
  if (!std::isfinite(options.cylinder_length) || options.cylinder_length <= 0.0) {
    throw ArgumentError("DemoArmOptions::cylinder_length must be positive and finite");
  }
  if (!std::isfinite(options.blend_width) || options.blend_width <= 0.0 ||
      options.blend_width > options.cylinder_length) {
    throw ArgumentError("DemoArmOptions::blend_width must lie in (0, cylinder_length]");
  }
  for (const double angle : options.bend_angles_degrees) {
    if (!std::isfinite(angle) || angle < -180.0 || angle > 180.0) {
      throw ArgumentError("DemoArmOptions::bend_angles_degrees holds an angle outside [-180, 180]");
    }
  }
}

// Rings from the south cap over the cylinder to the north cap, spaced about one segment length apart
// along the profile so that triangles come out close to equilateral.
std::vector<Ring> profile_rings(const DemoArmOptions& options) {
  const double r = options.radius;
  const double length = options.cylinder_length;
  const int segments = options.ring_segments;
  const double spacing = 2.0 * kPi * r / segments;
  const int cap_rings = segments / 4;
  const auto cylinder_steps = static_cast<std::int64_t>(std::max(1.0, std::round(length / spacing)));
  const std::int64_t ring_count = 2 * static_cast<std::int64_t>(cap_rings) + cylinder_steps - 1;
  if ((ring_count * segments + 2) > kMaxVertexCount) {
    throw ArgumentError("DemoArmOptions: the arm would have more than " + std::to_string(kMaxVertexCount) +
                        " vertices; lower ring_segments or cylinder_length");
  }

  std::vector<Ring> rings;
  rings.reserve(static_cast<size_t>(ring_count));
  const double latitude_step = 0.5 * kPi / cap_rings;
  for (int k = 1; k <= cap_rings; ++k) {
    const double latitude = -0.5 * kPi + k * latitude_step;
    rings.push_back({r * std::sin(latitude), r * std::cos(latitude)});
  }
  for (std::int64_t m = 1; m < cylinder_steps; ++m) {
    rings.push_back({length * static_cast<double>(m) / static_cast<double>(cylinder_steps), r});
  }
  for (int k = 0; k < cap_rings; ++k) {
    const double latitude = k * latitude_step;
    rings.push_back({length + r * std::sin(latitude), r * std::cos(latitude)});
  }
  return rings;
}

// Every other ring is turned by half a segment, which makes the strips between rings near-equilateral.
Eigen::MatrixX3d rest_vertices(const std::vector<Ring>& rings, const DemoArmOptions& options) {
  const int segments = options.ring_segments;
  const auto ring_count = static_cast<Eigen::Index>(rings.size());
  Eigen::MatrixX3d vertices(ring_count * segments + 2, 3);
  vertices.row(0) << -options.radius, 0.0, 0.0;
  for (Eigen::Index i = 0; i < ring_count; ++i) {
    const double half_turn = (i % 2 == 1) ? 0.5 : 0.0;
    for (int j = 0; j < segments; ++j) {
      const double angle = 2.0 * kPi * (j + half_turn) / segments;
      const Ring& ring = rings[static_cast<size_t>(i)];
      vertices.row(1 + i * segments + j) << ring.x, ring.radius * std::cos(angle), ring.radius * std::sin(angle);
    }
  }
  vertices.row(vertices.rows() - 1) << options.cylinder_length + options.radius, 0.0, 0.0;
  return vertices;
}

// Faces wound so that normals point out of the capsule.
Eigen::MatrixX3i capsule_faces(Eigen::Index ring_count, int segments) {
  const Eigen::Index vertex_count = ring_count * segments + 2;
  const int south_pole = 0;
  const auto north_pole = static_cast<int>(vertex_count - 1);
  auto ring_vertex = [segments](Eigen::Index ring, int j) {
    return static_cast<int>(1 + ring * segments + ((j % segments) + segments) % segments);
  };

  Eigen::MatrixX3i faces(2 * static_cast<Eigen::Index>(segments) * ring_count, 3);
  Eigen::Index f = 0;
  for (int j = 0; j < segments; ++j) faces.row(f++) << ring_vertex(0, j), south_pole, ring_vertex(0, j + 1);
  for (Eigen::Index i = 0; i + 1 < ring_count; ++i) {
    const bool lower_is_turned = (i % 2 == 1);
    for (int j = 0; j < segments; ++j) {
      if (!lower_is_turned) {
        // Upper vertex j sits between lower vertices j and j + 1.
        faces.row(f++) << ring_vertex(i, j), ring_vertex(i, j + 1), ring_vertex(i + 1, j);
        faces.row(f++) << ring_vertex(i + 1, j), ring_vertex(i, j + 1), ring_vertex(i + 1, j + 1);
      } else {
        // Lower vertex j sits between upper vertices j and j + 1.
        faces.row(f++) << ring_vertex(i, j), ring_vertex(i, j + 1), ring_vertex(i + 1, j + 1);
        faces.row(f++) << ring_vertex(i + 1, j), ring_vertex(i, j), ring_vertex(i + 1, j + 1);
      }
    }
  }
  for (int j = 0; j < segments; ++j) {
    faces.row(f++) << ring_vertex(ring_count - 1, j), ring_vertex(ring_count - 1, j + 1), north_pole;
  }
  return faces;
}

// Weight of the second bone: 0 before the blend zone, 1 after it, smoothstep in between.
double second_bone_weight(double x, const DemoArmOptions& options) {
  const double start = 0.5 * (options.cylinder_length - options.blend_width);
  const double t = std::clamp((x - start) / options.blend_width, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Linear blend skinning: the first bone stays put, the second turns about +z through the joint.
Eigen::MatrixX3d bent_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& rest, double angle_degrees,
                               const DemoArmOptions& options) {
  const double angle = angle_degrees * kPi / 180.0;
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double joint_x = 0.5 * options.cylinder_length;
  Eigen::MatrixX3d bent = rest;
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const double weight = second_bone_weight(rest(v, 0), options);
    if (weight == 0.0) continue;
    const double dx = rest(v, 0) - joint_x;
    const double dy = rest(v, 1);
    const double rotated_x = joint_x + c * dx - s * dy;
    const double rotated_y = s * dx + c * dy;
    bent(v, 0) += weight * (rotated_x - rest(v, 0));
    bent(v, 1) += weight * (rotated_y - rest(v, 1));
  }
  return bent;
}

std::string pose_name(double angle_degrees) {
  std::ostringstream name;
  name << "bend-" << angle_degrees;
  return name.str();
}

}  // namespace

PoseSet make_demo_arm(const DemoArmOptions& options) {
  check_options(options);
  const std::vector<Ring> rings = profile_rings(options);
  Eigen::MatrixX3d rest = rest_vertices(rings, options);
  PoseSet poses(capsule_faces(static_cast<Eigen::Index>(rings.size()), options.ring_segments));
  std::vector<Eigen::MatrixX3d> bent;
  bent.reserve(options.bend_angles_degrees.size());
  for (const double angle : options.bend_angles_degrees) bent.push_back(bent_vertices(rest, angle, options));
  poses.add_pose(std::move(rest), "rest");
  for (size_t i = 0; i < bent.size(); ++i) poses.add_pose(std::move(bent[i]), pose_name(options.bend_angles_degrees[i]));
  return poses;
}

}  // namespace posekit
