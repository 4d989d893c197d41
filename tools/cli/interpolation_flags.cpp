#include "interpolation_flags.hpp"

namespace posekit::cli {
namespace {

nlohmann::json percentiles_json(const ErrorPercentiles& p) {
  return {{"max", p.max}, {"p99.9", p.p999}, {"p99", p.p99}};
}

nlohmann::json error_json(const InterpolationError& error) {
  return {{"edge_length_relative", percentiles_json(error.edge_length)},
          {"dihedral_degrees", percentiles_json(error.dihedral_degrees)},
          {"collapsed_faces", error.collapsed_faces},
          {"folded_edges", error.folded_edges},
          {"finite", error.finite}};
}

}  // namespace

void add_interpolation_flags(CLI::App* command, InterpolationFlags& flags) {
  InterpolationOptions& c = flags.interpolation;
  command->add_option("--method", flags.method, "mixit, edge (whole mesh in edge space) or vertex (linear)")
      ->check(CLI::IsMember({"mixit", "edge", "vertex"}))
      ->capture_default_str();
  command->add_option("--joint-width", c.joint_width, "Triangle strips of a joint on each side of a part boundary")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  command->add_option("--rigidity-angle", c.segmentation.rigidity_angle_degrees,
                      "Automatic segmentation: largest rotation (degrees) between a part's faces")
      ->check(CLI::Range(0.01, 179.99))
      ->capture_default_str();
  command->add_option("--min-part-fraction", c.segmentation.min_part_fraction,
                      "Automatic segmentation: smaller parts (fraction of the faces) are merged")
      ->check(CLI::Range(0.0, 0.999))
      ->capture_default_str();
  command->add_option("--joint-iterations", c.joint_iterations, "Gauss-Newton iterations of each joint before alignment")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  command->add_option("--refinement-iterations", c.refinement_iterations,
                      "Gauss-Newton iterations of all joints with the parts' rigid motions after stitching")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  command->add_option("--projection-passes", c.projection_passes,
                      "Final local/global passes towards the interpolated lengths and dihedral angles")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  command->add_option("--projection-hinge-weight", c.projection_hinge_weight,
                      "Weight of dihedral angles against edge lengths in those passes")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  command->add_option("--edge-iterations", c.edge_iterations, "Gauss-Newton iterations of the edge method")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_option("--bending-weight", c.bending_weight,
                      "Weight of squared dihedral errors against squared relative edge-length errors")
      ->check(CLI::Range(1e-9, 1e9))
      ->capture_default_str();
}

InterpolationOptions interpolation_options(const InterpolationFlags& flags) {
  InterpolationOptions options = flags.interpolation;
  options.method = interpolation_method_from_string(flags.method);
  return options;
}

nlohmann::json interpolation_step_json(const Eigen::VectorXd& weights, const InterpolationStepReport& step,
                                       const InterpolationError& error) {
  return {{"weights", std::vector<double>(weights.data(), weights.data() + weights.size())},
          {"gauss_newton_iterations", step.gauss_newton_iterations},
          {"error", error_json(error)},
          {"seconds",
           {{"blend", step.seconds.blend},
            {"joints", step.seconds.joints},
            {"alignment", step.seconds.alignment},
            {"stitching", step.seconds.stitching},
            {"refinement", step.seconds.refinement},
            {"projection", step.seconds.projection},
            {"placement", step.seconds.placement},
            {"total", step.seconds.total}}}};
}

}  // namespace posekit::cli
