// Reads a pose, counts its self-intersecting faces and lists the compute devices.
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer MESH\n";
    return 2;
  }
  try {
    const posekit::Mesh mesh = posekit::read_mesh(argv[1]);
    const std::vector<int> faces = posekit::self_intersecting_faces(mesh.vertices, mesh.faces);
    std::cout << faces.size() << " self-intersecting faces\n";
    for (const posekit::BackendStatus& backend : posekit::list_backends()) {
      std::cout << backend.name << ": " << posekit::to_string(backend.state) << "\n";
    }
  } catch (const posekit::Error& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
  return 0;
}
