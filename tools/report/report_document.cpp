#include "report_document.hpp"

#include "base64.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string_view>

namespace posekit::report {
namespace {

constexpr double kQuantizationLevels = 65535.0;

size_t bytes_hash(const Eigen::MatrixX3d& vertices) {
  return std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(vertices.data()),
                                                        static_cast<size_t>(vertices.size()) * sizeof(double)));
}

// The box every position of the report is quantized in: 16 bits per axis over what is shown.
struct QuantizationBox {
  Eigen::Vector3d origin = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d top = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  void include(const Eigen::Ref<const Eigen::MatrixX3d>& points) {
    if (points.rows() == 0) return;
    origin = origin.cwiseMin(points.colwise().minCoeff().transpose());
    top = top.cwiseMax(points.colwise().maxCoeff().transpose());
  }
  Eigen::Vector3d step() const {
    Eigen::Vector3d s = (top - origin) / kQuantizationLevels;
    for (int k = 0; k < 3; ++k) {
      if (!(s(k) > 0.0)) s(k) = 1.0;  // a flat axis: every value is the origin
    }
    return s;
  }
  std::string encode(const Eigen::Ref<const Eigen::MatrixX3d>& points) const {
    const Eigen::Vector3d s = step();
    std::vector<std::uint16_t> quantized(static_cast<size_t>(points.rows()) * 3);
    for (Eigen::Index v = 0; v < points.rows(); ++v) {
      for (int k = 0; k < 3; ++k) {
        const double level = std::round((points(v, k) - origin(k)) / s(k));
        quantized[static_cast<size_t>(3 * v + k)] = static_cast<std::uint16_t>(std::clamp(level, 0.0, kQuantizationLevels));
      }
    }
    return base64_of(quantized);
  }
};

std::string encode_faces(const Eigen::MatrixX3i& faces, int vertex_count, int& index_bytes) {
  if (vertex_count <= 65535) {
    index_bytes = 2;
    std::vector<std::uint16_t> indices(static_cast<size_t>(faces.size()));
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      for (int c = 0; c < 3; ++c) indices[static_cast<size_t>(3 * f + c)] = static_cast<std::uint16_t>(faces(f, c));
    }
    return base64_of(indices);
  }
  index_bytes = 4;
  std::vector<std::uint32_t> indices(static_cast<size_t>(faces.size()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) indices[static_cast<size_t>(3 * f + c)] = static_cast<std::uint32_t>(faces(f, c));
  }
  return base64_of(indices);
}

// Per-vertex values as 8-bit levels of 0 .. `max`.
std::string encode_scalar(const Eigen::VectorXd& values, double max) {
  std::vector<std::uint8_t> levels(static_cast<size_t>(values.size()));
  for (Eigen::Index v = 0; v < values.size(); ++v) {
    const double fraction = max > 0.0 && std::isfinite(values(v)) ? values(v) / max : 0.0;
    levels[static_cast<size_t>(v)] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(fraction, 0.0, 1.0)));
  }
  return base64_of(levels);
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

}  // namespace

ReportDocument::ReportDocument(std::string job, std::string title, std::string command,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces, double diagonal)
    : job_(std::move(job)), title_(std::move(title)), command_(std::move(command)), faces_(faces), diagonal_(diagonal) {}

int ReportDocument::vertex_count() const { return poses_.empty() ? 0 : static_cast<int>(poses_.front().rows()); }

int ReportDocument::add_pose(const Eigen::Ref<const Eigen::MatrixX3d>& vertices) {
  if (!poses_.empty() && vertices.rows() != poses_.front().rows()) {
    throw ArgumentError("report: a pose of " + std::to_string(vertices.rows()) + " vertices in a report of " +
                        std::to_string(poses_.front().rows()));
  }
  Eigen::MatrixX3d pose = vertices;
  const size_t hash = bytes_hash(pose);
  for (size_t i = 0; i < poses_.size(); ++i) {
    if (pose_hashes_[i] == hash && poses_[i] == pose) return static_cast<int>(i);
  }
  poses_.push_back(std::move(pose));
  pose_hashes_.push_back(hash);
  return static_cast<int>(poses_.size() - 1);
}

void ReportDocument::add_summary(std::string label, std::string value) {
  summary_.emplace_back(std::move(label), std::move(value));
}

nlohmann::json ReportDocument::data() const {
  if (poses_.empty()) throw Error("report: no pose to show");
  const size_t frame_count = frame_names.size();
  if (frame_count == 0) throw Error("report: no frame");
  if (!frame_regions.empty() && frame_regions.size() != frame_count) throw Error("report: regions not given per frame");

  QuantizationBox box;
  for (const Eigen::MatrixX3d& pose : poses_) box.include(pose);
  for (const Panel& panel : panels) {
    if (panel.frames.size() != frame_count) {
      throw Error("report: panel '" + panel.title + "' has " + std::to_string(panel.frames.size()) + " frames, not " +
                  std::to_string(frame_count));
    }
    for (const PanelFrame& frame : panel.frames) {
      if (frame.pose < 0 || frame.pose >= static_cast<int>(poses_.size())) {
        throw Error("report: panel '" + panel.title + "' shows pose " + std::to_string(frame.pose) + " of " +
                    std::to_string(poses_.size()));
      }
      box.include(frame.points);
    }
  }

  nlohmann::json summary = nlohmann::json::array();
  for (const auto& [label, value] : summary_) summary.push_back({{"label", label}, {"value", value}});
  int index_bytes = 4;
  nlohmann::json mesh{{"vertex_count", vertex_count()},
                      {"face_count", faces_.rows()},
                      {"faces", encode_faces(faces_, vertex_count(), index_bytes)},
                      {"origin", vector_json(box.origin)},
                      {"step", vector_json(box.step())},
                      {"diagonal", diagonal_}};
  mesh["index_bytes"] = index_bytes;
  nlohmann::json poses = nlohmann::json::array();
  for (const Eigen::MatrixX3d& pose : poses_) poses.push_back(box.encode(pose));

  nlohmann::json panels_json = nlohmann::json::array();
  for (const Panel& panel : panels) {
    nlohmann::json frames = nlohmann::json::array();
    for (const PanelFrame& frame : panel.frames) {
      nlohmann::json entry{{"pose", frame.pose}};
      if (frame.scalar.size() > 0) {
        if (!panel.colour_map) throw Error("report: panel '" + panel.title + "' has values but no colour map");
        if (frame.scalar.size() != vertex_count()) throw Error("report: panel '" + panel.title + "' values not per vertex");
        entry["scalar"] = encode_scalar(frame.scalar, panel.colour_map->max);
      }
      if (!frame.face_sets.empty()) {
        nlohmann::json sets = nlohmann::json::array();
        for (const FaceSet& set : frame.face_sets) {
          std::vector<std::uint32_t> faces(set.faces.begin(), set.faces.end());
          sets.push_back({{"faces", base64_of(faces)}, {"colour", set.colour}, {"label", set.label}});
        }
        entry["face_sets"] = std::move(sets);
      }
      if (!frame.markers.empty()) {
        nlohmann::json markers = nlohmann::json::array();
        for (const Marker& marker : frame.markers) {
          markers.push_back({{"position", vector_json(marker.position)}, {"label", marker.label}});
        }
        entry["markers"] = std::move(markers);
      }
      if (frame.points.rows() > 0) entry["points"] = box.encode(frame.points);
      frames.push_back(std::move(entry));
    }
    nlohmann::json panel_json{{"title", panel.title}, {"frames", std::move(frames)}};
    if (panel.colour_map) {
      panel_json["colour_map"] = {
          {"label", panel.colour_map->label}, {"max", panel.colour_map->max}, {"unit", panel.colour_map->unit}};
    }
    panels_json.push_back(std::move(panel_json));
  }

  nlohmann::json frames{{"names", frame_names}};
  if (!frame_regions.empty()) {
    nlohmann::json regions = nlohmann::json::array();
    for (const std::vector<Region>& list : frame_regions) {
      nlohmann::json entries = nlohmann::json::array();
      for (const Region& region : list) {
        entries.push_back({{"label", region.label}, {"center", vector_json(region.center)}, {"radius", region.radius}});
      }
      regions.push_back(std::move(entries));
    }
    frames["regions"] = std::move(regions);
  }
  nlohmann::json plots_json = nlohmann::json::array();
  for (const Plot& plot : plots) plots_json.push_back({{"label", plot.label}, {"values", plot.values}});
  nlohmann::json tables_json = nlohmann::json::array();
  for (const Table& table : tables) {
    tables_json.push_back({{"title", table.title}, {"columns", table.columns}, {"rows", table.rows}});
  }
  return {{"posekit_report", 1}, {"job", job_},        {"title", title_},   {"command", command_},
          {"summary", summary},  {"mesh", mesh},       {"poses", poses},    {"frames", frames},
          {"panels", panels_json}, {"plots", plots_json}, {"tables", tables_json}};
}

std::string format_number(double value, int digits) {
  std::ostringstream text;
  text << std::setprecision(digits) << value;
  return text.str();
}

}  // namespace posekit::report
