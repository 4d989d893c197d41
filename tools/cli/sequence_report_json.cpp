#include "sequence_report_json.hpp"

#include "correction_report_json.hpp"

namespace posekit::cli {

nlohmann::json sequence_report_json(const SequenceReport& report, const std::vector<FrameCorrection>& frames,
                                    const std::vector<std::string>& names, const std::string& device) {
  const SequenceCoherence& c = report.coherence;
  nlohmann::json sequence = {
      {"device", device},
      {"frames", report.frames},
      {"corrected_frames", report.corrected_frames},
      {"carried_frames", report.carried_frames},
      {"touched_frames", report.touched_frames},
      {"failed_frames", report.failed_frames},
      {"frames_with_new_faces", report.frames_with_new_faces},
      {"bounding_box_diagonal", report.bounding_box_diagonal},
      {"coherence",
       {{"vertices", c.vertices},
        {"largest_offset_change", c.largest_offset_change},
        {"largest_offset_change_alone", c.largest_offset_change_alone},
        {"acceleration_p99_ratio", c.acceleration_p99_ratio},
        {"acceleration_max_ratio", c.acceleration_max_ratio},
        {"acceleration_p99_ratio_alone", c.acceleration_p99_ratio_alone},
        {"acceleration_max_ratio_alone", c.acceleration_max_ratio_alone}}},
      {"seconds", {{"total", report.seconds}, {"correction", report.correction_seconds}, {"coherence", report.coherence_seconds}}}};
  nlohmann::json entries = nlohmann::json::array();
  for (size_t t = 0; t < frames.size(); ++t) {
    const FrameCorrection& frame = frames[t];
    nlohmann::json entry = {{"name", names[t]},
                            {"corrected", frame.corrected},
                            {"reused", frame.reused},
                            {"carried", frame.carried},
                            {"carried_scale", frame.carried_scale},
                            {"stretched_faces", frame.stretched_faces},
                            {"seconds", frame.seconds},
                            {"touched", frame.touched},
                            {"target_new_faces", frame.target_new_faces},
                            {"new_faces", frame.new_faces},
                            {"own_share", frame.own_share},
                            {"distance_to_target",
                             {{"median", frame.median_distance_to_target}, {"max", frame.max_distance_to_target}}}};
    if (!frame.error.empty()) entry["error"] = frame.error;
    if (frame.corrected && !frame.report.stages.empty()) entry["correction"] = correction_report_json(frame.report);
    entries.push_back(std::move(entry));
  }
  return {{"sequence", std::move(sequence)}, {"frames", std::move(entries)}};
}

}  // namespace posekit::cli
