// The OBJ structure scan: mirrors CGAL::IO::read_OBJ line by line (CGAL 5.5, Stream_support/IO/OBJ.h).
#include <algorithm>
#include <array>
#include <climits>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh_file_scan.hpp"
#include "mesh/text_scan.hpp"
#include "posekit/error.hpp"

namespace posekit::detail {
namespace {

// Statements CGAL's OBJ reader accepts and skips; any other statement makes it fail.
constexpr std::array<std::string_view, 45> kSkippedStatements = {
    "vt",     "vn",       "vp",     "bevel",      "lod",       "ctech",  "c_interp", "usemap", "usemtl",
    "stech",  "d_interp", "mtllib", "shadow_obj", "trace_obj", "o",      "g",        "s",      "p",
    "cstype", "deg",      "step",   "bmat",       "con",       "curv",   "curv2",    "surf",   "parm",
    "trim",   "hole",     "scrv",   "sp",         "end",       "surf_1", "q0_1",     "q1_1",   "curv2d_1",
    "surf_2", "q0_2",     "q1_2",   "curv2d_2",   "bsp",       "bzp",    "cdc",      "cdp",    "res"};

// CGAL skips up to 256 characters after each face index (the "/vt/vn" part); a longer entry would be
// misread, so the scan refuses it.
constexpr std::size_t kMaxFaceEntryLength = 200;

bool is_skipped_statement(std::string_view keyword) {
  if (keyword.front() == '#') return true;
  return std::find(kSkippedStatements.begin(), kSkippedStatements.end(), keyword) != kSkippedStatements.end();
}

bool has_control_bytes(std::string_view line) {
  return std::any_of(line.begin(), line.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return (byte < 0x20 && !is_blank(c)) || byte == 0x7f;
  });
}

class ObjScanner {
 public:
  ObjScanner(std::string_view text, const std::string& file) : lines_(text), file_(file) {}

  ObjScan run() {
    std::string_view line;
    while (lines_.next(line)) {
      split_tokens(line, tokens_);
      if (tokens_.empty()) continue;
      const std::string_view keyword = tokens_.front();
      if (keyword == "v") {
        check_vertex();
      } else if (keyword == "f") {
        check_face();
      } else if (!is_skipped_statement(keyword)) {
        if (has_control_bytes(line)) fail("binary data, this is not a text OBJ file");
        fail("unsupported OBJ statement " + quote(keyword));
      }
    }
    if (result_.vertex_count == 0) throw InputError(file_, 0, "the file has no vertices");
    if (result_.face_lines.empty()) throw InputError(file_, 0, "the file has no faces");
    for (const auto& [line, index] : forward_references_) {
      if (index > static_cast<long long>(result_.vertex_count)) {
        throw InputError(file_, line, out_of_range(index));
      }
    }
    return std::move(result_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    std::string message = problem;
    if (lines_.at_unterminated_line()) message += " (the file ends inside this line: is it truncated?)";
    throw InputError(file_, lines_.line_number(), message);
  }

  std::string out_of_range(long long index) const {
    return "face index " + std::to_string(index) + " is out of range: the file has " +
           std::to_string(result_.vertex_count) + " vertices";
  }

  void check_vertex() {
    const std::size_t coordinates = tokens_.size() - 1;
    for (std::size_t k = 1; k <= std::min<std::size_t>(coordinates, 3); ++k) {
      double value = 0.0;
      switch (parse_double(tokens_[k], value)) {
        case NumberStatus::ok:
          break;
        case NumberStatus::non_finite:
          fail("vertex coordinate " + quote(tokens_[k]) + " is not a finite number");
        default:
          fail("vertex coordinate " + quote(tokens_[k]) + " is not a number");
      }
    }
    if (coordinates < 3) {
      fail("vertex has " + count_of(static_cast<long long>(coordinates), "coordinate", "coordinates") +
           "; 3 are needed");
    }
    ++result_.vertex_count;
  }

  void check_face() {
    std::size_t corners = 0;
    long long largest = 0;
    for (std::size_t k = 1; k < tokens_.size() && tokens_[k].front() != '#'; ++k) {
      const std::string_view entry = tokens_[k];
      if (entry.size() > kMaxFaceEntryLength) fail("face entry " + quote(entry) + " is too long");
      const std::string_view index_text = entry.substr(0, entry.find('/'));
      long long index = 0;
      switch (parse_integer(index_text, index)) {
        case NumberStatus::ok:
          break;
        case NumberStatus::out_of_range:
          fail("face index " + std::string(index_text.substr(0, 40)) + " is out of range");
        default:
          fail("face index " + quote(index_text) + " is not a whole number");
      }
      if (index == 0) fail("face index 0 is invalid: OBJ indices start at 1");
      if (index < 0) fail("negative face index " + std::to_string(index) + ": relative OBJ indices are not supported");
      if (index > INT_MAX) fail("face index " + std::to_string(index) + " is out of range");
      largest = std::max(largest, index);
      ++corners;
    }
    if (corners != 3) {
      fail("face has " + count_of(static_cast<long long>(corners), "vertex", "vertices") +
           "; only triangles are supported");
    }
    // OBJ lets a face name a vertex defined further down; the range is checked at the end.
    if (largest > static_cast<long long>(result_.vertex_count)) {
      forward_references_.emplace_back(lines_.line_number(), largest);
    }
    result_.face_lines.push_back(lines_.line_number());
  }

  LineReader lines_;
  const std::string& file_;
  std::vector<std::string_view> tokens_;
  std::vector<std::pair<long, long long>> forward_references_;
  ObjScan result_;
};

}  // namespace

ObjScan scan_obj(std::string_view text, const std::string& file) { return ObjScanner(text, file).run(); }

}  // namespace posekit::detail
