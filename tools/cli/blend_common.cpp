#include "blend_common.hpp"

#include "cli_common.hpp"

#include <posekit/error.hpp>
#include <posekit/laplace_beltrami.hpp>
#include <posekit/mesh_io.hpp>

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace posekit::cli {

void add_blend_options(CLI::App* command, BlendCommandOptions& options) {
  command->add_option("--examples", options.examples,
                      "Example poses of one connectivity; the first is the reference for weights and clusters")
      ->required()
      ->expected(1, -1);
  add_blend_tuning_options(command, options);
}

void add_blend_tuning_options(CLI::App* command, BlendCommandOptions& options) {
  BlendOptions& b = options.blend;
  command->add_option("--weights", options.weights,
                      "Skinning weights (one row of numbers per vertex) instead of Laplace-Beltrami eigenfunctions");
  command->add_option("--dictionary", options.dictionary,
                      "lbo: Laplace-Beltrami weights; skeleton: change to weights learned from the examples (skinning "
                      "decomposition); auto: the one that rebuilds two held-out examples better from 20 of their points")
      ->check(CLI::IsMember({"lbo", "skeleton", "auto"}))
      ->capture_default_str();
  command->add_option("--bones", b.skinning.bones, "Bones of the skinning decomposition (0 chooses the count)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command->add_option("--skinning-cache", options.skinning_cache,
                      "File of the skinning decomposition: read when it exists (it must match the examples), else "
                      "made and written");
  command->add_option("--eigenfunctions", b.eigenfunctions, "Laplace-Beltrami eigenfunctions used as weights")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--atom-fraction", b.atom_fraction, "Fraction of dictionary atoms kept by k-medoids")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  command->add_option("--clusters", b.rotation_clusters,
                      "Rotation clusters (0 with --weights: one per weight function)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  command->add_option("--constraint-weight", b.constraint_weight, "Weight of each constraint against ARAP")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--smoothness-weight", b.smoothness_weight, "Weight of the smoothness of the blended maps")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--sparsity", b.sparsity, "Elastic-net L1 weight of the initial solve, in [0, 1)")
      ->check(CLI::Range(0.0, 0.999999))
      ->capture_default_str();
  command->add_option("--average-iterations", b.average_iterations, "Local/global iterations with average ARAP")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_option("--minimal-iterations", b.minimal_iterations, "Local/global iterations with minimal ARAP")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_flag("--no-scale", options.no_scale, "Keep the global scale at 1 instead of estimating it");
  command->add_flag("--choice-after-solve", b.example_choice_after_solve,
                    "Pick the minimal-ARAP example by its energy after its global step (slower)");
}

PoseSet read_examples(const BlendCommandOptions& options) {
  std::vector<std::filesystem::path> files(options.examples.begin(), options.examples.end());
  std::vector<std::string> warnings;
  PoseSet examples = read_pose_set(files, &warnings);
  print_warnings(warnings);
  try {
    check_laplace_beltrami_mesh(examples.pose(0), examples.faces());
  } catch (const ArgumentError& error) {
    throw InputError(options.examples.front(), 0, std::string("cannot serve as the reference pose: ") + error.what());
  }
  return examples;
}

BlendedDeformer make_deformer(const PoseSet& examples, const BlendCommandOptions& options) {
  BlendOptions blend = options.blend;
  blend.estimate_scale = !options.no_scale;
  blend.dictionary = options.dictionary == "skeleton" ? DictionaryChoice::skeleton
                     : options.dictionary == "auto"   ? DictionaryChoice::automatic
                                                      : DictionaryChoice::lbo;
  if (!options.weights.empty() && blend.dictionary != DictionaryChoice::lbo) {
    throw ArgumentError("--weights is a dictionary of its own; it cannot be combined with --dictionary " + options.dictionary);
  }
  if (!options.skinning_cache.empty() && blend.dictionary == DictionaryChoice::lbo) {
    throw ArgumentError("--skinning-cache needs --dictionary skeleton or auto");
  }
  if (blend.dictionary != DictionaryChoice::lbo && examples.pose_count() < 2) {
    throw ArgumentError("--dictionary " + options.dictionary +
                        " learns bones from the examples and needs at least two of them, got " +
                        std::to_string(examples.pose_count()));
  }
  if (blend.skinning.bones > examples.vertex_count()) {
    throw ArgumentError("--bones " + std::to_string(blend.skinning.bones) + " exceeds the " +
                        std::to_string(examples.vertex_count()) + " vertices of the examples");
  }
  if (!options.skinning_cache.empty()) {
    const std::filesystem::path cache = options.skinning_cache;
    if (std::filesystem::exists(cache)) {
      const SkinningDecomposition skinning = read_skinning_decomposition(cache, examples);
      if (blend.skinning.bones > 0 && skinning.bone_count() != blend.skinning.bones) {
        throw InputError(options.skinning_cache, 0,
                         "the cache holds " + std::to_string(skinning.bone_count()) + " bones, not the " +
                             std::to_string(blend.skinning.bones) + " of --bones; remove it to make it anew");
      }
      return BlendedDeformer(examples, skinning, blend);
    }
    const std::filesystem::path folder = cache.has_parent_path() ? cache.parent_path() : std::filesystem::path(".");
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) {
      throw InputError(options.skinning_cache, 0, "cannot write the skinning cache: the folder " + folder.string() +
                                                      " does not exist");
    }
    const SkinningDecomposition skinning = decompose_skinning(examples, blend.skinning);
    write_skinning_decomposition(cache, skinning, examples);
    return BlendedDeformer(examples, skinning, blend);
  }
  if (options.weights.empty()) {
    if (blend.eigenfunctions >= examples.vertex_count()) {
      throw ArgumentError("--eigenfunctions " + std::to_string(blend.eigenfunctions) + " must be below the " +
                          std::to_string(examples.vertex_count()) + " vertices of the examples");
    }
    if (blend.rotation_clusters == 0) throw ArgumentError("--clusters 0 needs --weights");
    return BlendedDeformer(examples, blend);
  }
  const Eigen::MatrixXd weights = read_skinning_weights(options.weights, examples.vertex_count());
  return BlendedDeformer(examples, weights, blend);
}

BlendResult deform_to_points(BlendedDeformer& deformer, PointConstraints& constraints, nlohmann::json& report) {
  const bool ambiguous =
      std::any_of(constraints.groups.begin(), constraints.groups.end(), [](const std::string& g) { return !g.empty(); });
  if (!ambiguous) {
    std::vector<LinearConstraint> rows;
    for (int v : constraints.vertices) rows.push_back(LinearConstraint::vertex(v));
    deformer.set_constraints(rows);
    return deformer.deform(constraints.positions);
  }
  const std::vector<std::vector<int>> assignments = permissible_assignments(constraints.vertices, constraints.groups);
  CorrespondenceChoice choice = choose_correspondence(deformer, constraints.positions, assignments);
  report["correspondence"] = {{"assignments", assignments.size()},
                              {"chosen", choice.assignment},
                              {"vertices", choice.vertices},
                              {"energies", choice.energies}};
  constraints.vertices = choice.vertices;
  return std::move(choice.result);
}

nlohmann::json setup_json(const BlendSetupReport& setup) {
  return {{"vertices", setup.vertices},
          {"examples", setup.examples},
          {"weights", setup.weights},
          {"atoms", {{"full", setup.full_atoms}, {"kept", setup.atoms}}},
          {"clusters", setup.clusters},
          {"dictionary", setup.dictionary},
          {"bones", setup.bones},
          {"skinning_error", setup.skinning_error},
          {"trial", {{"examples", setup.trial.examples}, {"lbo", setup.trial.lbo}, {"skeleton", setup.trial.skeleton}}},
          {"seconds",
           {{"weights", setup.seconds.weights},
            {"dictionary", setup.seconds.dictionary},
            {"clusters", setup.seconds.clusters},
            {"system", setup.seconds.system},
            {"skinning", setup.seconds.skinning},
            {"trial", setup.seconds.trial},
            {"total", setup.seconds.total}}}};
}

nlohmann::json deformation_json(const BlendResult& result, const PoseSet& examples) {
  nlohmann::json iterations = nlohmann::json::array();
  for (const BlendIteration& it : result.iterations) {
    nlohmann::json entry = {{"stage", it.stage}, {"energy", it.energy}, {"scale", it.scale}};
    if (it.example >= 0) entry["example"] = examples.pose_name(it.example);
    iterations.push_back(entry);
  }
  nlohmann::json json = {{"energy", result.energy},
                         {"scale", result.scale},
                         {"iterations", iterations},
                         {"seconds", result.seconds}};
  json["closest_example"] = result.closest_example >= 0 ? nlohmann::json(examples.pose_name(result.closest_example))
                                                        : nlohmann::json(nullptr);
  return json;
}

void add_scan_fit_options(CLI::App* command, ScanFitOptions& f) {
  command->add_option("--icp-iterations", f.iterations, "Rounds of non-rigid ICP")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_option("--scan-points", f.max_scan_points, "Scan points used as constraints per round")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  command->add_option("--scan-weight", f.scan_weight, "Weight of a scan point against a feature point")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--normal-angle", f.max_normal_angle_degrees, "Largest angle between matched normals, degrees")
      ->check(CLI::Range(1e-6, 180.0))
      ->capture_default_str();
  command->add_option("--rejection-factor", f.rejection_factor, "Drop matches farther than this times the median")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

void registration_json(const ScanRegistration& registration, const PoseSet& examples, const BlendedDeformer& deformer,
                       nlohmann::json& report) {
  nlohmann::json rounds = nlohmann::json::array();
  for (const ScanFitIteration& it : registration.iterations) {
    rounds.push_back({{"matches", it.matches},
                      {"median_distance", it.median_distance},
                      {"energy", it.energy},
                      {"seconds", it.seconds}});
  }
  const Eigen::VectorXd& d = registration.distances;
  report["setup"] = setup_json(deformer.setup_report());
  report["initial"] = deformation_json(registration.initial, examples);
  report["deformation"] = deformation_json(registration.deformation, examples);
  report["icp"] = rounds;
  std::vector<double> sorted(d.data(), d.data() + d.size());
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  report["correspondence_of_scan_vertices"] = {
      {"mesh_vertex", std::vector<int>(registration.correspondence.data(),
                                       registration.correspondence.data() + registration.correspondence.size())},
      {"distance", std::vector<double>(d.data(), d.data() + d.size())},
      {"median_distance", sorted.empty() ? 0.0 : sorted[sorted.size() / 2]},
      {"max_distance", d.size() > 0 ? d.maxCoeff() : 0.0}};
}

}  // namespace posekit::cli
