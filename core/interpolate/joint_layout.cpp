#include "interpolate/joint_layout.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace posekit::interpolation {
namespace {

// Edge-connected components of the faces for which `member` holds, each with its vertices.
template <typename Member>
std::vector<MeshComponent> components(const Eigen::Ref<const Eigen::MatrixX3i>& faces, const EdgeMap& edges,
                                      const AdjacencyLists& incident_faces, Member member) {
  const int face_count = static_cast<int>(faces.rows());
  std::vector<char> seen(static_cast<size_t>(face_count), 0);
  std::vector<MeshComponent> result;
  for (int start = 0; start < face_count; ++start) {
    if (seen[static_cast<size_t>(start)] || !member(start)) continue;
    MeshComponent component;
    seen[static_cast<size_t>(start)] = 1;
    component.faces.push_back(start);
    for (size_t next = 0; next < component.faces.size(); ++next) {
      const int f = component.faces[next];
      for (int corner = 0; corner < 3; ++corner) {
        for (const int g : incident_faces[edges.face_edges(f, corner)]) {
          if (seen[static_cast<size_t>(g)] || !member(g) || !member.same(f, g)) continue;
          seen[static_cast<size_t>(g)] = 1;
          component.faces.push_back(g);
        }
      }
    }
    std::sort(component.faces.begin(), component.faces.end());
    for (const int f : component.faces) {
      for (int corner = 0; corner < 3; ++corner) component.vertices.push_back(faces(f, corner));
    }
    std::sort(component.vertices.begin(), component.vertices.end());
    component.vertices.erase(std::unique(component.vertices.begin(), component.vertices.end()),
                             component.vertices.end());
    result.push_back(std::move(component));
  }
  return result;
}

}  // namespace

JointLayout build_joint_layout(const Eigen::Ref<const Eigen::MatrixX3i>& faces, const Eigen::VectorXi& face_parts,
                               const EdgeMap& edges,
                               const AdjacencyLists& incident_faces, const AdjacencyLists& neighbours, int joint_width) {
  if (joint_width < 1) throw ArgumentError("joint width must be at least 1, got " + std::to_string(joint_width));
  const int face_count = static_cast<int>(faces.rows());
  const int vertex_count = neighbours.item_count();
  if (face_parts.size() != face_count) {
    throw ArgumentError("joint layout: " + std::to_string(face_parts.size()) + " part ids for " +
                        std::to_string(face_count) + " faces");
  }
  // A vertex on a part boundary has faces of two parts; strips count vertex rings from there.
  constexpr int kFar = std::numeric_limits<int>::max() / 2;
  std::vector<int> first_part(static_cast<size_t>(vertex_count), -1);
  std::vector<char> boundary(static_cast<size_t>(vertex_count), 0);
  for (int f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const auto v = static_cast<size_t>(faces(f, corner));
      if (first_part[v] < 0) first_part[v] = face_parts(f);
      else if (first_part[v] != face_parts(f)) boundary[v] = 1;
    }
  }
  std::vector<int> distance(static_cast<size_t>(vertex_count), kFar);
  std::vector<int> queue;
  for (int v = 0; v < vertex_count; ++v) {
    if (boundary[static_cast<size_t>(v)]) {
      distance[static_cast<size_t>(v)] = 0;
      queue.push_back(v);
    }
  }
  for (size_t next = 0; next < queue.size(); ++next) {
    const int v = queue[next];
    if (distance[static_cast<size_t>(v)] >= joint_width) continue;  // farther rings are not needed
    for (const int w : neighbours[v]) {
      if (distance[static_cast<size_t>(w)] != kFar) continue;
      distance[static_cast<size_t>(w)] = distance[static_cast<size_t>(v)] + 1;
      queue.push_back(w);
    }
  }
  JointLayout layout;
  layout.face_strip.resize(face_count);
  for (int f = 0; f < face_count; ++f) {
    int nearest = kFar;
    for (int corner = 0; corner < 3; ++corner) nearest = std::min(nearest, distance[static_cast<size_t>(faces(f, corner))]);
    layout.face_strip(f) = nearest == kFar ? 0 : nearest + 1;
  }
  const Eigen::VectorXi& strip = layout.face_strip;

  struct InJoint {
    const Eigen::VectorXi& strip;
    int width;
    bool operator()(int f) const { return strip(f) >= 1 && strip(f) <= width; }
    bool same(int, int) const { return true; }
  };
  struct InRigid {
    const Eigen::VectorXi& strip;
    const Eigen::VectorXi& parts;
    int width;
    bool operator()(int f) const { return strip(f) == 0 || strip(f) >= width; }
    bool same(int f, int g) const { return parts(f) == parts(g); }
  };
  layout.joints = components(faces, edges, incident_faces, InJoint{strip, joint_width});
  layout.rigid_pieces = components(faces, edges, incident_faces, InRigid{strip, face_parts, joint_width});
  for (const MeshComponent& joint : layout.joints) layout.joint_face_count += static_cast<int>(joint.faces.size());
  return layout;
}

}  // namespace posekit::interpolation
