// What an HTML report shows, independent of the job that made it: poses (stored once each), panels
// that show a pose per frame with colours, flagged faces and markers, per-frame regions, plots over
// the frames and tables. html_page() turns it into the page; docs/reports.md gives the data schema.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace posekit::report {

/// The legend of a panel's per-vertex values: 0 to `max`, shown in `unit` ("of the diagonal" is
/// shown as a percentage).
struct ColourMap {
  std::string label;
  double max = 0;
  std::string unit;
};

/// Faces drawn in one colour, e.g. the intersecting faces of a pose.
struct FaceSet {
  std::vector<int> faces;
  std::string colour;  ///< CSS hex colour, "#rrggbb"
  std::string label;
};

struct Marker {
  Eigen::Vector3d position;
  std::string label;
};

/// What one panel shows in one frame.
struct PanelFrame {
  int pose = 0;                    ///< index from ReportDocument::add_pose()
  Eigen::VectorXd scalar;          ///< per vertex, in the panel's colour map units; empty: none
  std::vector<FaceSet> face_sets;  ///< later sets are drawn over earlier ones
  std::vector<Marker> markers;
  Eigen::MatrixX3d points;         ///< a point cloud drawn with the mesh (e.g. a scan); may be empty
};

struct Panel {
  std::string title;
  std::optional<ColourMap> colour_map;
  std::vector<PanelFrame> frames;  ///< one per frame of the document
};

/// A place worth a look, listed under "jump to region".
struct Region {
  std::string label;
  Eigen::Vector3d center;
  double radius = 0;
};

struct Plot {
  std::string label;
  std::vector<double> values;  ///< one per frame
};

struct Table {
  std::string title;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

/// Everything a report shows, for a mesh of one connectivity.
class ReportDocument {
 public:
  /// A report of `job` on meshes with the #F by 3 `faces`; `diagonal` (of the reference's bounding box)
  /// scales markers and the colour maps' "of the diagonal".
  ReportDocument(std::string job, std::string title, std::string command,
                 const Eigen::Ref<const Eigen::MatrixX3i>& faces, double diagonal);

  /// Index of `vertices` (#V by 3) among the stored poses; a vertex set equal to a stored one is not
  /// stored again, so frames that repeat a pose cost nothing.
  int add_pose(const Eigen::Ref<const Eigen::MatrixX3d>& vertices);

  void add_summary(std::string label, std::string value);

  std::vector<std::string> frame_names;          ///< one per frame; a single-result job has one
  std::vector<std::vector<Region>> frame_regions;  ///< per frame, or empty
  std::vector<Panel> panels;
  std::vector<Plot> plots;
  std::vector<Table> tables;

  /// The report's data, schema version 1 (docs/reports.md): positions quantized to 16 bits in a box
  /// around everything shown, binary arrays base64-encoded. Throws Error when the document is not
  /// whole (a panel without a frame per name, a pose index out of range).
  nlohmann::json data() const;

  const std::string& title() const { return title_; }
  double diagonal() const { return diagonal_; }
  int vertex_count() const;

 private:
  std::string job_;
  std::string title_;
  std::string command_;
  Eigen::MatrixX3i faces_;
  double diagonal_;
  std::vector<std::pair<std::string, std::string>> summary_;
  std::vector<Eigen::MatrixX3d> poses_;
  std::vector<size_t> pose_hashes_;
};

/// A number with `digits` significant digits, as the report's tables and summaries print them.
std::string format_number(double value, int digits = 3);

}  // namespace posekit::report
