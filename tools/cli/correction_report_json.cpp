#include "correction_report_json.hpp"

namespace posekit::cli {
namespace {

nlohmann::json drift_json(const DriftReport& drift) {
  return {{"before", {{"median", drift.before.median}, {"max", drift.before.max}}},
          {"after", {{"median", drift.after.median}, {"max", drift.after.max}}}};
}

nlohmann::json region_json(const FieldRegionReport& region) {
  nlohmann::json rounds = nlohmann::json::array();
  for (const RbfFitRound& round : region.fit.rounds) {
    rounds.push_back({{"centers", round.centers},
                      {"max_squared_error", round.max_squared_error},
                      {"assembly_seconds", round.assembly_seconds},
                      {"factorization_seconds", round.factorization_seconds},
                      {"evaluation_seconds", round.evaluation_seconds}});
  }
  return {{"vertices", region.vertices},
          {"unconstrained_vertices", region.unconstrained_vertices},
          {"constraints", region.constraints},
          {"time_scale", region.time_scale},
          {"fit",
           {{"rounds", region.fit.rounds.size()},
            {"centers", region.fit.centers},
            {"max_squared_error", region.fit.max_squared_error},
            {"converged", region.fit.converged},
            {"per_round", rounds}}},
          {"rk45",
           {{"accepted_steps", region.integration.accepted_steps},
            {"rejected_steps", region.integration.rejected_steps},
            {"rhs_evaluations", region.integration.rhs_evaluations},
            {"failures", region.integration.failures}}},
          {"drift", drift_json(region.drift)}};
}

nlohmann::json field_json(const FieldReport& field) {
  nlohmann::json regions = nlohmann::json::array();
  for (const FieldRegionReport& region : field.regions) regions.push_back(region_json(region));
  return {{"key_frames", field.key_frames},
          {"tested_poses", field.tested_poses},
          {"classification",
           {{"reference_intersecting_faces", field.reference_intersecting_faces},
            {"target_intersecting_faces", field.target_intersecting_faces},
            {"excluded_vertices", field.excluded_vertices},
            {"near_intersection_vertices", field.near_intersection_vertices}}},
          {"whole_mesh", field.whole_mesh},
          {"collar_rings", field.collar_rings},
          {"region_vertices", field.region_vertices},
          {"regions", regions},
          {"fit_tolerance", field.fit_tolerance},
          {"constraints", field.constraints()},
          {"centers", field.centers()},
          {"converged", field.converged()},
          {"new_faces_after_integration", field.new_faces_after_integration},
          {"reproduction", {{"vertices", field.reproduced_vertices}, {"skipped", field.reproduction_skipped}}},
          {"seconds",
           {{"normalization", field.seconds.normalization},
            {"key_frames", field.seconds.key_frames},
            {"classification", field.seconds.classification},
            {"regions", field.seconds.regions},
            {"fitting", field.seconds.fitting},
            {"integration", field.seconds.integration},
            {"drift_compensation", field.seconds.drift_compensation},
            {"reproduction", field.seconds.reproduction}}}};
}

nlohmann::json stage_json(const StageReport& stage) {
  nlohmann::json details = nlohmann::json::object();
  for (const auto& [name, value] : stage.details) details[name] = value;
  return {{"name", stage.name},
          {"ran", stage.ran},
          {"skipped", stage.skipped},
          {"kept", stage.kept},
          {"new_faces_before", stage.new_faces_before},
          {"new_faces_after", stage.new_faces_after},
          {"regions", stage.regions},
          {"vertices", stage.vertices},
          {"seconds", stage.seconds},
          {"note", stage.note},
          {"details", details}};
}

nlohmann::json result_json(const ResultReport& result) {
  return {{"intersecting_faces",
           {{"reference", result.reference_intersecting_faces},
            {"target", result.target_intersecting_faces},
            {"result", result.intersecting_faces},
            {"new", result.new_intersecting_faces}}},
          {"distance_to_target",
           {{"median", result.median_distance_to_target},
            {"max", result.max_distance_to_target},
            {"near_intersection_vertices", result.near_intersection_vertices},
            {"median_near_intersections", result.median_distance_near_intersections},
            {"bounding_box_diagonal", result.bounding_box_diagonal}}},
          {"changed_vertices", result.changed_vertices},
          {"distortion",
           {{"stretched_faces", result.stretched_faces},
            {"strongly_stretched_faces", result.strongly_stretched_faces},
            {"largest_stretch", result.largest_stretch}}}};
}

}  // namespace

nlohmann::json correction_report_json(const CorrectionReport& report) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageReport& stage : report.stages) stages.push_back(stage_json(stage));
  return {{"device", report.device},
          {"vertices", report.vertices},
          {"faces", report.faces},
          {"field", field_json(report.field)},
          {"stages", stages},
          {"result", result_json(report.result)},
          {"seconds", report.seconds}};
}

}  // namespace posekit::cli
