#include "cli_common.hpp"
#include "commands.hpp"
#include "html_page.hpp"
#include "html_report_option.hpp"
#include "interpolation_flags.hpp"
#include "job_pages.hpp"

#include <posekit/error.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/rigid_segmentation.hpp>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace posekit::cli {
namespace {

struct InterpolateCommandOptions {
  std::vector<std::string> poses;
  std::vector<std::string> weights;
  std::string output;
  std::string segmentation;
  std::string save_segmentation;
  std::string report;
  std::string html;
  InterpolationOptions interpolation;  // from the flags, with the segmentation read
  InterpolationFlags flags;
};

// A usage error: one line on stderr and exit status 2, like any other command-line mistake.
[[noreturn]] void usage_error(const std::string& message) { throw CLI::ValidationError(message); }

double parse_number(const std::string& text, const std::string& weight) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value)) {
    usage_error("--weights: '" + weight + "' is not a number or a comma-separated list of numbers");
  }
  return value;
}

// "t" means (1 - t, t) for two poses; "w0,w1,...,wK-1" gives one weight per pose.
Eigen::VectorXd parse_weights(const std::string& text, int pose_count) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) values.push_back(parse_number(item, text));
  if (!text.empty() && text.back() == ',') values.push_back(parse_number("", text));
  if (values.size() == 1 && pose_count == 2) return two_pose_weights(values.front());
  if (static_cast<int>(values.size()) != pose_count) {
    usage_error("--weights: '" + text + "' has " + std::to_string(values.size()) +
                (values.size() == 1 ? " entry for " : " entries for ") +
                std::to_string(pose_count) + " poses (give one weight per pose, separated by commas" +
                (pose_count == 2 ? ", or one number t for (1 - t, t))" : ")"));
  }
  const Eigen::VectorXd weights = Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  try {
    return normalized_weights(weights, pose_count);
  } catch (const ArgumentError& error) {
    usage_error(std::string("--weights: '") + text + "': " + error.what());
  }
}

// The file of output `index` of `count`: `pattern` itself for one output, "{}" replaced by the index
// (zero-padded to the width of the largest) for several.
std::string output_name(const std::string& pattern, size_t index, size_t count) {
  if (count == 1) return pattern;
  std::string number = std::to_string(index);
  const size_t width = std::to_string(count - 1).size();
  if (number.size() < width) number.insert(0, width - number.size(), '0');
  std::string name = pattern;
  for (size_t at = name.find("{}"); at != std::string::npos; at = name.find("{}", at + number.size())) {
    name.replace(at, 2, number);
  }
  return name;
}

// Everything that depends only on the command line, checked before any file is read: weight vectors.
std::vector<Eigen::VectorXd> checked_weights(const InterpolateCommandOptions& options) {
  const int pose_count = static_cast<int>(options.poses.size());
  std::vector<Eigen::VectorXd> weights;
  for (const std::string& text : options.weights) weights.push_back(parse_weights(text, pose_count));
  if (weights.size() > 1 && options.output.find("{}") == std::string::npos) {
    usage_error("-o: " + std::to_string(weights.size()) + " weights give " + std::to_string(weights.size()) +
                " outputs; put {} in the output name where the output number goes (e.g. -o mid-{}.obj)");
  }
  return weights;
}

void run_interpolate(InterpolateCommandOptions options, const std::vector<Eigen::VectorXd>& weights) {
  options.interpolation = interpolation_options(options.flags);
  if (!options.html.empty()) report::check_report_destination(options.html, "--html");
  {
    std::vector<std::string> outputs;
    for (size_t i = 0; i < weights.size(); ++i) {
      outputs.push_back(output_name(options.output, i, weights.size()));
      mesh_format_from_extension(outputs.back());
    }
    std::vector<std::string> warnings;
    std::vector<std::filesystem::path> files(options.poses.begin(), options.poses.end());
    PoseSet poses = read_pose_set(files, &warnings);
    print_warnings(warnings);
    const bool mixit = options.interpolation.method == InterpolationMethod::mixit;
    if (!options.segmentation.empty()) {
      options.interpolation.face_parts =
          read_part_labels(options.segmentation, poses.vertex_count(), poses.faces());
      if (!mixit) print_warnings({"--segmentation is used by --method mixit only; ignored"});
    }
    if (!options.save_segmentation.empty() && !mixit) {
      print_warnings({"--save-segmentation is used by --method mixit only; nothing saved"});
    }

    PoseInterpolator interpolator(std::move(poses), options.interpolation);
    const InterpolationLayout& layout = interpolator.layout();
    const PrecomputationTimes& precomputation = interpolator.precomputation_seconds();
    std::vector<Eigen::MatrixX3d> results;
    nlohmann::json output_reports = nlohmann::json::array();
    for (size_t i = 0; i < weights.size(); ++i) {
      InterpolationStepReport step;
      results.push_back(interpolator.interpolate(weights[i], &step));
      const InterpolationError error = interpolator.error(results.back(), weights[i]);
      if (!error.finite) throw Error("the interpolation for weights '" + options.weights[i] + "' is not finite");
      nlohmann::json entry = interpolation_step_json(weights[i], step, error);
      entry["file"] = outputs[i];
      output_reports.push_back(std::move(entry));
    }
    // Outputs only once every one of them is computed.
    const Eigen::MatrixX3i& faces = interpolator.poses().faces();
    for (size_t i = 0; i < results.size(); ++i) write_mesh(outputs[i], Mesh{results[i], faces});
    if (!options.save_segmentation.empty() && mixit) {
      write_part_labels(options.save_segmentation, interpolator.face_parts());
    }
    if (!options.html.empty()) {
      std::vector<std::string> pose_names;
      for (const std::string& file : options.poses) pose_names.push_back(std::filesystem::path(file).filename().string());
      report::write_html_report(options.html, report::interpolation_page(interpolator, pose_names, weights, results,
                                                                         outputs, command_line()));
    }
    if (!options.report.empty()) {
      const InterpolationOptions& used = interpolator.options();
      const nlohmann::json report{
          {"method", options.flags.method},
          {"poses", options.poses},
          {"vertices", interpolator.poses().vertex_count()},
          {"faces", faces.rows()},
          {"options",
           {{"joint_width", used.joint_width},
            {"rigidity_angle_degrees", used.segmentation.rigidity_angle_degrees},
            {"min_part_fraction", used.segmentation.min_part_fraction},
            {"joint_iterations", used.joint_iterations},
            {"refinement_iterations", used.refinement_iterations},
            {"edge_iterations", used.edge_iterations},
            {"projection_passes", used.projection_passes},
            {"projection_hinge_weight", used.projection_hinge_weight},
            {"bending_weight", used.bending_weight},
            {"alignment_sweeps", used.alignment_sweeps}}},
          {"segmentation",
           {{"source", options.segmentation.empty() ? std::string("automatic") : options.segmentation},
            {"parts", layout.parts},
            {"rigid_pieces", layout.rigid_pieces},
            {"joints", layout.joints},
            {"joint_faces", layout.joint_faces},
            {"joint_edges", layout.joint_edges},
            {"rigid_vertices", layout.rigid_vertices},
            {"mixed_dimension", layout.mixed_dimension},
            {"edge_dimension", layout.edge_dimension}}},
          {"precomputation_seconds",
           {{"edge_space", precomputation.edge_space},
            {"segmentation", precomputation.segmentation},
            {"layout", precomputation.layout},
            {"registration", precomputation.registration},
            {"factorization", precomputation.factorization},
            {"total", precomputation.total}}},
          {"outputs", output_reports}};
      write_text_atomically(options.report, report.dump(2) + "\n");
    }

    std::cout << std::fixed << std::setprecision(1);
    if (mixit) {
      std::cout << layout.parts << " parts, " << layout.rigid_pieces << " rigid pieces, " << layout.joints
                << " joints (" << 100.0 * layout.joint_faces / static_cast<double>(faces.rows())
                << "% of the faces); ";
    }
    std::cout << "precomputation " << 1000.0 * precomputation.total << " ms\n";
    for (size_t i = 0; i < results.size(); ++i) {
      const nlohmann::json& r = output_reports[i];
      std::cout << std::setprecision(2) << outputs[i] << ": weights " << options.weights[i]
                << "; edge-length error p99 " << 100.0 * r["error"]["edge_length_relative"]["p99"].get<double>()
                << "%, dihedral error p99 " << r["error"]["dihedral_degrees"]["p99"].get<double>() << " deg; "
                << std::setprecision(1) << 1000.0 * r["seconds"]["total"].get<double>() << " ms\n";
    }
  }
}

}  // namespace

void add_interpolate_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<InterpolateCommandOptions>();
  auto* command = app.add_subcommand(
      "interpolate",
      "In-between poses of an articulated shape in a mixed shape space (MixIT) or a baseline");
  command->footer(
      "Weights: with two poses, --weights t gives (1 - t) * POSE0 + t * POSE1 (t = 0: the first pose, 1: the\n"
      "second; outside [0, 1] extrapolates). With K poses, each weight is K comma-separated numbers\n"
      "summing to 1 (within 1e-4), e.g. --weights 0.25,0.25,0.25,0.25. Several weights give several\n"
      "outputs from one precomputation: put {} in -o for the output's number (from 0, zero-padded),\n"
      "e.g. --weights 0.25 0.5 0.75 -o mid-{}.obj writes mid-0.obj, mid-1.obj and mid-2.obj.\n"
      "A --segmentation file holds one non-negative part id per vertex or per face (white space\n"
      "separated, '#' comments). Exit status: 0 on success, 1 for bad input, 2 for a usage error.");
  command->add_option("POSE", options->poses, "Poses of one shape (same connectivity), at least two")
      ->required()
      ->expected(2, 1 << 20);
  command->add_option("--weights", options->weights, "One weight vector per output (see below)")
      ->required()
      ->expected(1, 1 << 20);
  command->add_option("-o,--output", options->output, "Output mesh (OBJ, OFF or PLY); {} numbers several")
      ->required();
  command->add_option("--segmentation", options->segmentation, "Part ids per vertex or per face instead of the automatic segmentation");
  command->add_option("--save-segmentation", options->save_segmentation, "Write the part id of every face used (mixit)");
  command->add_option("--report", options->report, "Write a JSON report (errors, stage times) to this file");
  add_html_option(command, options->html);
  add_interpolation_flags(command, options->flags);
  command->callback([options, &exit_status] {
    const std::vector<Eigen::VectorXd> weights = checked_weights(*options);  // usage errors: status 2
    exit_status = run_guarded([&] { run_interpolate(*options, weights); });
  });
}

}  // namespace posekit::cli
