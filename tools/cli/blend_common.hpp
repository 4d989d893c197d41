// What posekit deform and posekit register share: the deformer's options on the command line,
// reading the examples, building the deformer, resolving ambiguous feature points, JSON reports.
#pragma once

#include <posekit/blend_files.hpp>
#include <posekit/blended_deformation.hpp>
#include <posekit/feature_correspondence.hpp>
#include <posekit/mesh.hpp>
#include <posekit/partial_registration.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace posekit::cli {

/// The command-line settings of a BlendedDeformer.
struct BlendCommandOptions {
  std::vector<std::string> examples;
  std::string weights;  ///< skinning weight file; empty: Laplace-Beltrami eigenfunctions
  std::string dictionary = "lbo";  ///< lbo, skeleton or auto
  std::string skinning_cache;      ///< file of the skinning decomposition, read when it exists, else written
  bool no_scale = false;
  BlendOptions blend;
};

/// Adds --examples, --weights and the deformer's tuning options to `command`.
void add_blend_options(CLI::App* command, BlendCommandOptions& options);

/// The same without --examples (for callers that hold the examples already).
void add_blend_tuning_options(CLI::App* command, BlendCommandOptions& options);

/// The examples, read and checked (same connectivity; the first one fit to carry the weights: a
/// degenerate reference is an InputError naming its file).
PoseSet read_examples(const BlendCommandOptions& options);

/// The deformer for `examples` with the options' weights (file or eigenfunctions) and dictionary; with
/// a skinning cache, its decomposition is read (checked against the examples) or made and written.
BlendedDeformer make_deformer(const PoseSet& examples, const BlendCommandOptions& options);

/// Deforms `deformer` to the point constraints; when some share a group, every permissible assignment
/// is tried and the one of least energy kept (its vertices are written back into `constraints`).
/// Fills `report["correspondence"]` in that case.
BlendResult deform_to_points(BlendedDeformer& deformer, PointConstraints& constraints, nlohmann::json& report);

/// JSON of the precomputation and of one deformation.
nlohmann::json setup_json(const BlendSetupReport& setup);
nlohmann::json deformation_json(const BlendResult& result, const PoseSet& examples);

/// Adds register's non-rigid ICP options (--icp-iterations, --scan-points, ...) to `command`.
void add_scan_fit_options(CLI::App* command, ScanFitOptions& fit);

/// Fills `report` with the registration's setup, initial and final deformation, ICP rounds and the
/// mesh vertex matched to every scan vertex.
void registration_json(const ScanRegistration& registration, const PoseSet& examples, const BlendedDeformer& deformer,
                       nlohmann::json& report);

}  // namespace posekit::cli
