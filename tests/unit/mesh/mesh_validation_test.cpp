#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "posekit/error.hpp"
#include "posekit/mesh_validation.hpp"

namespace posekit {
namespace {

Mesh tetrahedron() {
  Mesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.faces.resize(4, 3);
  mesh.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return mesh;
}

// Runs validate_mesh and returns the message of the InputError it must throw.
std::string validation_error(const Mesh& mesh) {
  try {
    validate_mesh(mesh, "source.obj");
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "source.obj");
    EXPECT_EQ(error.line(), 0);
    return error.what();
  }
  ADD_FAILURE() << "validate_mesh accepted the mesh";
  return {};
}

TEST(ValidateMesh, AcceptsACleanMeshWithoutWarnings) {
  std::vector<std::string> warnings;
  EXPECT_NO_THROW(validate_mesh(tetrahedron(), "source.obj", &warnings));
  EXPECT_TRUE(warnings.empty());
}

TEST(ValidateMesh, EmptyMeshesAreErrors) {
  Mesh no_vertices;
  EXPECT_EQ(validation_error(no_vertices), "source.obj: the mesh has no vertices");
  Mesh no_faces = tetrahedron();
  no_faces.faces.resize(0, 3);
  EXPECT_EQ(validation_error(no_faces), "source.obj: the mesh has no faces");
}

TEST(ValidateMesh, NonFiniteCoordinatesAreErrors) {
  Mesh mesh = tetrahedron();
  mesh.vertices(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(validation_error(mesh).find("vertex 2 has a non-finite coordinate"), std::string::npos);
  mesh.vertices(2, 1) = 0.0;
  mesh.vertices(3, 2) = -std::numeric_limits<double>::infinity();
  EXPECT_NE(validation_error(mesh).find("vertex 3 has a non-finite coordinate (-inf)"), std::string::npos);
}

TEST(ValidateMesh, IndicesOutsideTheVerticesAreErrors) {
  Mesh mesh = tetrahedron();
  mesh.faces(3, 1) = 4;
  EXPECT_EQ(validation_error(mesh), "source.obj: face 3 uses vertex index 4, out of range: the mesh has 4 vertices");
  mesh.faces(3, 1) = -1;
  EXPECT_EQ(validation_error(mesh), "source.obj: face 3 uses negative vertex index -1");
}

TEST(FindMeshDefects, CountsUnreferencedVerticesAndDegenerateFaces) {
  Mesh mesh;
  mesh.vertices.resize(7, 3);
  // Vertices 4 and 6 are used by no face; 5 lies on the line through 0 and 1.
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 9, 9, 9, 3, 0, 0, 7, 7, 7;
  mesh.faces.resize(6, 3);
  mesh.faces << 0, 2, 1, 0, 1, 3, 0, 3, 3, 1, 2, 3, 0, 1, 5, 2, 2, 2;
  const MeshDefects defects = find_mesh_defects(mesh);
  EXPECT_EQ(defects.unreferenced_vertex_count, 2);
  EXPECT_EQ(defects.first_unreferenced_vertex, 4);
  EXPECT_EQ(defects.degenerate_face_count, 3);
  EXPECT_EQ(defects.first_degenerate_face, 2);

  std::vector<std::string> warnings;
  validate_mesh(mesh, "source.obj", &warnings);
  ASSERT_EQ(warnings.size(), 2U);
  EXPECT_EQ(warnings[0], "source.obj: 2 unreferenced vertices (used by no face; first: vertex 4)");
  EXPECT_EQ(warnings[1], "source.obj: 3 degenerate faces (repeated vertex or zero area; first: face 2)");
}

TEST(FindMeshDefects, TinyButNonZeroAreaIsNotDegenerate) {
  Mesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0.5, 1e-300, 0;
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;
  EXPECT_EQ(find_mesh_defects(mesh).degenerate_face_count, 0);
  mesh.vertices(2, 1) = 0.0;
  EXPECT_EQ(find_mesh_defects(mesh).degenerate_face_count, 1);
  EXPECT_EQ(find_mesh_defects(mesh).unreferenced_vertex_count, 0);
  EXPECT_EQ(find_mesh_defects(mesh).first_unreferenced_vertex, -1);
}

}  // namespace
}  // namespace posekit
