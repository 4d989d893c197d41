// The OFF structure scan: mirrors CGAL 5.5's File_header_OFF and File_scanner_OFF. The header is read
// word by word; after it every vertex and face is one line, found after blanks and '#' comment lines.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <climits>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh_file_scan.hpp"
#include "mesh/text_scan.hpp"
#include "posekit/error.hpp"

namespace posekit::detail {
namespace {

// The OFF header keyword: [ST][C][N][4][n] followed by OFF (or SKEL, which has no faces).
struct OffVariant {
  bool recognized = false;
  bool supported = false;
  bool has_normals = false;
  bool has_colors = false;
};

OffVariant parse_variant(std::string_view keyword) {
  OffVariant variant;
  std::size_t i = 0;
  const auto take = [&](std::string_view prefix) {
    if (keyword.substr(i, prefix.size()) != prefix) return false;
    i += prefix.size();
    return true;
  };
  const bool textures = take("ST");
  variant.has_colors = take("C");
  variant.has_normals = take("N");
  const bool homogeneous = take("4");
  const bool dimensional = take("n");
  const std::string_view rest = keyword.substr(i);
  variant.recognized = rest == "OFF" || rest == "SKEL";
  // CGAL reads texture coordinates and homogeneous or n-dimensional vertices with unchecked entry
  // positions; plain, colored and normal-carrying 3D vertices are all posekit needs.
  variant.supported = variant.recognized && rest == "OFF" && !textures && !homogeneous && !dimensional;
  return variant;
}

class OffScanner {
 public:
  OffScanner(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  SoupCounts run() {
    const OffVariant variant = read_keyword();
    read_counts();
    for (std::size_t i = 0; i < counts_.vertex_count; ++i) {
      if (!next_record()) truncated(i, false);
      check_vertex(variant);
    }
    for (std::size_t i = 0; i < counts_.face_count; ++i) {
      if (!next_record()) truncated(i, true);
      check_face(variant);
    }
    return counts_;
  }

 private:
  [[noreturn]] void fail(long line, const std::string& problem) const {
    std::string message = problem;
    if (record_unterminated_) message += " (the file ends inside this line: is it truncated?)";
    throw InputError(file_, line, message);
  }

  [[noreturn]] void truncated(std::size_t complete, bool in_faces) const {
    throw InputError(file_, counts_line_,
                     "the header announces " +
                         count_of(static_cast<long long>(counts_.vertex_count), "vertex", "vertices") + " and " +
                         count_of(static_cast<long long>(counts_.face_count), "face", "faces") +
                         ", but the file ends after " +
                         (in_faces ? count_of(static_cast<long long>(complete), "face", "faces")
                                   : count_of(static_cast<long long>(complete), "vertex", "vertices")) +
                         ": it is truncated");
  }

  bool at_end() const { return position_ >= text_.size(); }

  void skip_spaces() {
    while (!at_end() && is_space(text_[position_])) {
      if (text_[position_] == '\n') ++line_;
      ++position_;
    }
  }

  void skip_spaces_and_comments() {
    for (skip_spaces(); !at_end() && text_[position_] == '#'; skip_spaces()) {
      while (!at_end() && text_[position_] != '\n') ++position_;
    }
  }

  std::string_view next_word() {
    skip_spaces();
    const std::size_t begin = position_;
    while (!at_end() && !is_space(text_[position_])) ++position_;
    return text_.substr(begin, position_ - begin);
  }

  // Moves to the next vertex or face line (as CGAL's skip_comment then getline) and splits it.
  bool next_record() {
    skip_spaces_and_comments();
    if (at_end()) return false;
    record_line_ = line_;
    const std::size_t end = text_.find('\n', position_);
    record_unterminated_ = end == std::string_view::npos;
    const std::size_t stop = record_unterminated_ ? text_.size() : end;
    split_tokens(strip_comment(text_.substr(position_, stop - position_)), tokens_);
    position_ = record_unterminated_ ? text_.size() : end + 1;
    ++line_;
    return true;
  }

  OffVariant read_keyword() {
    skip_spaces_and_comments();
    if (at_end()) throw InputError(file_, 0, "the file has no OFF header");
    const long keyword_line = line_;
    // CGAL takes the first character, then letters and digits, then drops the character after them.
    const std::size_t begin = position_++;
    while (!at_end() && std::isalnum(static_cast<unsigned char>(text_[position_])) != 0) ++position_;
    const std::string_view keyword = text_.substr(begin, position_ - begin);
    if (!at_end()) {
      if (text_[position_] == '\n') ++line_;
      ++position_;
    }
    const OffVariant variant = parse_variant(keyword);
    if (!variant.recognized) {
      const std::size_t line_end = text_.find('\n', begin);
      const std::string_view first_line =
          text_.substr(begin, line_end == std::string_view::npos ? text_.size() - begin : line_end - begin);
      for (const char c : first_line) {
        const auto byte = static_cast<unsigned char>(c);
        if ((byte < 0x20 && !is_blank(c)) || byte == 0x7f) {
          throw InputError(file_, keyword_line, "binary data, this is not a text OFF file");
        }
      }
      throw InputError(file_, keyword_line, "bad OFF header: it starts with " + quote(keyword) + " instead of 'OFF'");
    }
    if (!variant.supported) {
      throw InputError(file_, keyword_line,
                       "unsupported OFF variant " + quote(keyword) + "; posekit reads OFF, COFF, NOFF and CNOFF");
    }
    return variant;
  }

  void read_counts() {
    skip_spaces_and_comments();
    counts_line_ = line_;
    if (!at_end() && std::isdigit(static_cast<unsigned char>(text_[position_])) == 0) {
      const std::string_view word = next_word();
      if (word.substr(0, 6) == "BINARY") {
        throw InputError(file_, counts_line_, "binary OFF is not supported; write ASCII OFF or PLY");
      }
      throw InputError(file_, counts_line_,
                       "bad OFF header: expected the vertex, face and edge counts, found " + quote(word));
    }
    // CGAL doubles the edge count and scales the sum of the counts by 2.1 in int arithmetic; counts up
    // to 10^9 (far more than any file holds) keep that arithmetic in range.
    constexpr long long kMaxCount = 1000000000;
    std::array<long long, 3> counts = {0, 0, 0};
    const std::array<const char*, 3> names = {"vertex", "face", "edge"};
    for (std::size_t k = 0; k < counts.size(); ++k) {
      const std::string_view word = next_word();
      if (word.empty()) {
        throw InputError(file_, counts_line_, "bad OFF header: the file ends before the vertex, face and edge counts");
      }
      if (parse_integer(word, counts[k]) != NumberStatus::ok || counts[k] < 0 || counts[k] > kMaxCount) {
        throw InputError(file_, counts_line_,
                         std::string("bad OFF header: ") + names[k] + " count " + quote(word) +
                             " is not a whole number from 0 to " + std::to_string(kMaxCount));
      }
    }
    if (counts[0] + counts[1] > kMaxCount) {
      throw InputError(file_, counts_line_,
                       "bad OFF header: more than " + std::to_string(kMaxCount) + " vertices and faces together");
    }
    counts_.vertex_count = static_cast<std::size_t>(counts[0]);
    counts_.face_count = static_cast<std::size_t>(counts[1]);
    if (counts_.vertex_count == 0) throw InputError(file_, counts_line_, "the file has no vertices");
    if (counts_.face_count == 0) throw InputError(file_, counts_line_, "the file has no faces");
  }

  // Every entry of a line must be a number: CGAL stops at the first entry it cannot read and then
  // looks for colors at positions that depend on how many it read.
  void check_numbers(std::size_t first, std::size_t end, const char* what) {
    for (std::size_t k = first; k < end && k < tokens_.size(); ++k) {
      double value = 0.0;
      const NumberStatus status = parse_double(tokens_[k], value);
      if (status == NumberStatus::non_finite)
        fail(record_line_, std::string(what) + " " + quote(tokens_[k]) + " is not a finite number");
      if (status != NumberStatus::ok)
        fail(record_line_, std::string(what) + " " + quote(tokens_[k]) + " is not a number");
    }
  }

  // CGAL reads one color index, or three or four components; it remembers that colors were seen and
  // then expects them on every later line. It casts them to int or unsigned char unchecked, so an
  // index must be from 0 to INT_MAX and components from 0 to 255 (integers) or 0 to 1 (fractions).
  void check_colors(std::size_t first, bool& colors_seen, const char* what) {
    const std::size_t color_entries = tokens_.size() - first;
    if (color_entries == 2) fail(record_line_, std::string(what) + " has 2 color components; 1, 3 or 4 are needed");
    if (color_entries == 0 && colors_seen)
      fail(record_line_, std::string(what) + " has no color but earlier ones have");
    if (color_entries == 0) return;
    colors_seen = true;
    std::array<double, 3> values = {0.0, 0.0, 0.0};
    const std::size_t used = color_entries == 1 ? 1 : 3;
    for (std::size_t k = 0; k < used; ++k) parse_double(tokens_[first + k], values[k]);
    if (used == 1) {
      if (!(values[0] >= 0.0 && values[0] <= INT_MAX)) {
        fail(record_line_, std::string(what) + " color index " + quote(tokens_[first]) + " is out of range");
      }
      return;
    }
    const bool integral =
        std::all_of(values.begin(), values.end(), [](double value) { return std::floor(value) == value; });
    const double top = integral ? 255.0 : 1.0;
    if (!std::all_of(values.begin(), values.end(), [top](double value) { return value >= 0.0 && value <= top; })) {
      fail(record_line_,
           std::string(what) + " color components must be whole numbers from 0 to 255 or fractions from 0 to 1");
    }
  }

  void check_vertex(const OffVariant& variant) {
    check_numbers(0, 3, "vertex coordinate");
    check_numbers(3, tokens_.size(), "vertex entry");
    const std::size_t needed = variant.has_normals ? 6 : 3;
    if (tokens_.size() < needed) {
      fail(record_line_, "vertex has " + count_of(static_cast<long long>(tokens_.size()), "number", "numbers") + "; " +
                             std::to_string(needed) +
                             (variant.has_normals ? " (3 coordinates and a normal) are needed" : " are needed"));
    }
    if (variant.has_colors) check_colors(needed, vertex_colors_seen_, "vertex");
  }

  void check_face(const OffVariant& variant) {
    long long corners = 0;
    if (parse_integer(tokens_[0], corners) != NumberStatus::ok) {
      fail(record_line_, "face vertex count " + quote(tokens_[0]) + " is not a whole number");
    }
    if (corners != 3)
      fail(record_line_, "face has " + count_of(corners, "vertex", "vertices") + "; only triangles are supported");
    if (tokens_.size() < 4) {
      fail(record_line_, "face lists " +
                             count_of(static_cast<long long>(tokens_.size() - 1), "vertex index", "vertex indices") +
                             "; 3 are needed");
    }
    for (std::size_t k = 1; k <= 3; ++k) {
      long long index = 0;
      const NumberStatus status = parse_integer(tokens_[k], index);
      if (status == NumberStatus::ok && index < 0) {
        fail(record_line_, "negative face index " + std::to_string(index));
      }
      if (status == NumberStatus::out_of_range ||
          (status == NumberStatus::ok && index >= static_cast<long long>(counts_.vertex_count))) {
        fail(record_line_, "face index " + std::string(tokens_[k].substr(0, 40)) + " is out of range: the file has " +
                               std::to_string(counts_.vertex_count) + " vertices");
      }
      if (status != NumberStatus::ok) fail(record_line_, "face index " + quote(tokens_[k]) + " is not a whole number");
    }
    check_numbers(4, tokens_.size(), "face color component");
    if (variant.has_colors) check_colors(4, face_colors_seen_, "face");
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t position_ = 0;
  long line_ = 1;
  long counts_line_ = 0;
  long record_line_ = 0;
  bool record_unterminated_ = false;
  bool vertex_colors_seen_ = false;
  bool face_colors_seen_ = false;
  std::vector<std::string_view> tokens_;
  SoupCounts counts_;
};

}  // namespace

SoupCounts scan_off(std::string_view text, const std::string& file) { return OffScanner(text, file).run(); }

}  // namespace posekit::detail
