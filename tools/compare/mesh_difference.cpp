// posekit_mesh_difference A B [--tolerance R]: the largest distance between corresponding vertices
// of two meshes with the same vertex count, absolute and as a fraction of the bounding-box diagonal
// of A. With --tolerance, exit status 1 when the fraction exceeds R. Bad input: one line on stderr,
// exit status 1; usage errors: exit status 2.
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  CLI::App app{"Largest distance between corresponding vertices of two meshes"};
  std::string first;
  std::string second;
  double tolerance = -1.0;
  app.add_option("A", first, "First mesh (OBJ, OFF or PLY); its bounding box is the scale")
      ->required();
  app.add_option("B", second, "Second mesh, with as many vertices as A")->required();
  app.add_option("--tolerance", tolerance,
                 "Fail (exit status 1) when the difference exceeds this fraction of the diagonal")
      ->check(CLI::NonNegativeNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;
  }
  try {
    const posekit::Mesh a = posekit::read_mesh(first);
    const posekit::Mesh b = posekit::read_mesh(second);
    if (a.vertices.rows() != b.vertices.rows()) {
      throw posekit::InputError(second, 0,
                                std::to_string(b.vertices.rows()) + " vertices, but " + first +
                                    " has " + std::to_string(a.vertices.rows()));
    }
    const double diagonal = posekit::bounding_box_diagonal(a.vertices);
    Eigen::Index worst = 0;
    const double largest =
        a.vertices.rows() == 0 ? 0.0 : (a.vertices - b.vertices).rowwise().norm().maxCoeff(&worst);
    const double fraction = diagonal > 0 ? largest / diagonal : 0.0;
    std::printf("max vertex difference %.6e (vertex %lld) = %.6e of the bounding-box diagonal %.6g\n",
                largest, static_cast<long long>(worst), fraction, diagonal);
    if (tolerance >= 0 && !(fraction <= tolerance)) {
      std::fprintf(stderr, "posekit_mesh_difference: %.6e exceeds the tolerance %.6e\n", fraction,
                   tolerance);
      return 1;
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "posekit_mesh_difference: error: %s\n", error.what());
    return 1;
  }
}
