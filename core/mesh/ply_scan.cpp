// The PLY structure scan: reads the header as CGAL 5.5's PLY_reader does, then walks every element
// item and property of the body (ASCII tokens or binary bytes) without building anything.
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh_file_scan.hpp"
#include "mesh/text_scan.hpp"
#include "posekit/error.hpp"

namespace posekit::detail {
namespace {

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<PlyType> ply_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::int8;
  if (name == "uchar" || name == "uint8") return PlyType::uint8;
  if (name == "short" || name == "int16") return PlyType::int16;
  if (name == "ushort" || name == "uint16") return PlyType::uint16;
  if (name == "int" || name == "int32") return PlyType::int32;
  if (name == "uint" || name == "uint32") return PlyType::uint32;
  if (name == "float" || name == "float32") return PlyType::float32;
  if (name == "double" || name == "float64") return PlyType::float64;
  return std::nullopt;
}

std::size_t byte_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 8;
}

bool is_real(PlyType type) { return type == PlyType::float32 || type == PlyType::float64; }

void integer_range(PlyType type, long long& low, long long& high) {
  switch (type) {
    case PlyType::int8:
      low = INT8_MIN;
      high = INT8_MAX;
      return;
    case PlyType::uint8:
      low = 0;
      high = UINT8_MAX;
      return;
    case PlyType::int16:
      low = INT16_MIN;
      high = INT16_MAX;
      return;
    case PlyType::uint16:
      low = 0;
      high = UINT16_MAX;
      return;
    case PlyType::int32:
      low = INT32_MIN;
      high = INT32_MAX;
      return;
    default:
      low = 0;
      high = UINT32_MAX;
      return;
  }
}

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;  // the item type for a list
  bool is_list = false;
  PlyType count_type = PlyType::uint8;
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> properties;
};

// The role a property plays for CGAL, so that its values get the matching checks.
enum class Role { other, coordinate, face_indices };

// One value of the body: an integer, or a real for float and double properties.
struct PlyValue {
  long long integer = 0;
  double real = 0.0;
};

class PlyScanner {
 public:
  PlyScanner(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  SoupCounts run() {
    read_header();
    find_mesh_elements();
    cursor_ = body_offset_;
    body_line_ = header_lines_ + 1;
    for (std::size_t e = 0; e < elements_.size(); ++e) walk_element(e);
    return counts_;
  }

 private:
  [[noreturn]] void fail(long line, const std::string& problem) const { throw InputError(file_, line, problem); }

  // ---- header -------------------------------------------------------------------------------

  void read_header() {
    LineReader lines(bytes_);
    std::string_view line;
    std::vector<std::string_view> tokens;
    if (!lines.next(line)) fail(0, "the file is empty");
    split_tokens(line, tokens);
    if (tokens.empty() || tokens.front() != "ply") {
      fail(1, "not a PLY file: the first line is " + quote(line) + " instead of 'ply'");
    }
    if (!lines.next(line)) fail(1, "the PLY header ends after its first line: the file is truncated");
    split_tokens(line, tokens);
    if (tokens.size() < 3 || tokens[0] != "format") {
      fail(2, "bad PLY header: expected 'format ascii 1.0' (or binary_little_endian, binary_big_endian), found " +
                  quote(line));
    }
    if (tokens[1] == "ascii") {
      encoding_ = PlyEncoding::ascii;
    } else if (tokens[1] == "binary_little_endian") {
      encoding_ = PlyEncoding::binary_little_endian;
    } else if (tokens[1] == "binary_big_endian") {
      encoding_ = PlyEncoding::binary_big_endian;
    } else {
      fail(2, "bad PLY header: unknown PLY format " + quote(tokens[1]));
    }
    while (lines.next(line)) {
      const long number = lines.line_number();
      split_tokens(line, tokens);
      if (tokens.empty()) fail(number, "bad PLY header: empty line");
      const std::string_view keyword = tokens.front();
      if (keyword == "end_header") {
        body_offset_ = lines.offset();
        header_lines_ = number;
        return;
      }
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "element") {
        read_element(tokens, number);
      } else if (keyword == "property") {
        read_property(tokens, number);
      } else {
        fail(number, "bad PLY header: unknown keyword " + quote(keyword));
      }
    }
    fail(lines.line_number(), "the PLY header has no end_header line: the file is truncated");
  }

  void read_element(const std::vector<std::string_view>& tokens, long line) {
    long long count = 0;
    if (tokens.size() != 3 || parse_integer(tokens[2], count) != NumberStatus::ok || count < 0) {
      fail(line, "bad PLY header: expected 'element NAME COUNT' with a count of 0 or more");
    }
    elements_.push_back(PlyElement{std::string(tokens[1]), static_cast<unsigned long long>(count), {}});
  }

  void read_property(const std::vector<std::string_view>& tokens, long line) {
    // CGAL appends a property to the last element, whether there is one or not.
    if (elements_.empty()) fail(line, "bad PLY header: a property comes before any element");
    PlyProperty property;
    if (tokens.size() >= 2 && tokens[1] == "list") {
      if (tokens.size() != 5) fail(line, "bad PLY header: expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
      const auto count_type = ply_type(tokens[2]);
      const auto item_type = ply_type(tokens[3]);
      if (!count_type || is_real(*count_type))
        fail(line, "bad PLY header: list count type " + quote(tokens[2]) + " is not an integer type");
      if (!item_type) fail(line, "bad PLY header: unknown property type " + quote(tokens[3]));
      property = PlyProperty{std::string(tokens[4]), *item_type, true, *count_type};
    } else {
      if (tokens.size() != 3) fail(line, "bad PLY header: expected 'property TYPE NAME'");
      const auto type = ply_type(tokens[1]);
      // CGAL skips a property of an unknown type, which shifts every later value.
      if (!type) fail(line, "bad PLY header: unknown property type " + quote(tokens[1]));
      property = PlyProperty{std::string(tokens[2]), *type, false, PlyType::uint8};
    }
    elements_.back().properties.push_back(std::move(property));
  }

  static std::optional<std::size_t> first_property(const PlyElement& element, std::string_view name) {
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      if (element.properties[p].name == name) return p;
    }
    return std::nullopt;
  }

  void find_mesh_elements() {
    std::optional<std::size_t> vertex;
    std::optional<std::size_t> face;
    for (std::size_t e = 0; e < elements_.size(); ++e) {
      const std::string& name = elements_[e].name;
      std::optional<std::size_t>* slot = nullptr;
      if (name == "vertex" || name == "vertices") slot = &vertex;
      if (name == "face" || name == "faces") slot = &face;
      // CGAL reads 'halfedge' elements with unchecked property types.
      if (name == "halfedge") fail(0, "PLY element 'halfedge' is not supported");
      if (slot == nullptr) continue;
      if (*slot) fail(0, "the PLY file has more than one " + name + " element");
      *slot = e;
    }
    if (!vertex || elements_[*vertex].count == 0) fail(0, "the file has no vertices");
    if (!face || elements_[*face].count == 0) fail(0, "the file has no faces");
    if (elements_[*vertex].count > INT_MAX || elements_[*face].count > INT_MAX) {
      fail(0, "the PLY file has more than " + std::to_string(INT_MAX) + " vertices or faces");
    }
    counts_.vertex_count = elements_[*vertex].count;
    counts_.face_count = elements_[*face].count;

    roles_.assign(elements_.size(), {});
    for (std::size_t e = 0; e < elements_.size(); ++e) roles_[e].assign(elements_[e].properties.size(), Role::other);

    // CGAL takes the first property of each name and, for x, y and z, insists on float or double.
    const PlyElement& vertices = elements_[*vertex];
    for (const char* axis : {"x", "y", "z"}) {
      const auto p = first_property(vertices, axis);
      if (!p || vertices.properties[*p].is_list || !is_real(vertices.properties[*p].type)) {
        fail(0, std::string("the PLY vertex element has no float or double property '") + axis + "'");
      }
      roles_[*vertex][*p] = Role::coordinate;
    }

    // CGAL looks for an int list, then a uint list, named vertex_indices, then vertex_index.
    const PlyElement& faces = elements_[*face];
    std::optional<std::size_t> indices;
    for (const char* name : {"vertex_indices", "vertex_index"}) {
      for (const PlyType type : {PlyType::int32, PlyType::uint32}) {
        const auto p = first_property(faces, name);
        if (!indices && p && faces.properties[*p].is_list && faces.properties[*p].type == type) indices = p;
      }
    }
    if (!indices) fail(0, "the PLY face element has no list of int or uint named 'vertex_indices'");
    roles_[*face][*indices] = Role::face_indices;
  }

  // ---- body -----------------------------------------------------------------------------------

  std::string item_name(std::size_t e, unsigned long long item) const {
    return elements_[e].name + " " + std::to_string(item);
  }

  [[noreturn]] void truncated(std::size_t e, unsigned long long item) const {
    fail(encoding_ == PlyEncoding::ascii ? body_line_ : 0, "the file ends inside " + item_name(e, item) + " of " +
                                                               std::to_string(elements_[e].count) +
                                                               ": it is truncated");
  }

  // Where a value is, for messages: the line in ASCII, the element item in binary.
  long value_line() const { return encoding_ == PlyEncoding::ascii ? token_line_ : 0; }
  std::string value_place(std::size_t e, unsigned long long item) const {
    return encoding_ == PlyEncoding::ascii ? "" : " (" + item_name(e, item) + ")";
  }

  bool next_token(std::string_view& token) {
    while (cursor_ < bytes_.size() && is_space(bytes_[cursor_])) {
      if (bytes_[cursor_] == '\n') ++body_line_;
      ++cursor_;
    }
    if (cursor_ >= bytes_.size()) return false;
    const std::size_t begin = cursor_;
    while (cursor_ < bytes_.size() && !is_space(bytes_[cursor_])) ++cursor_;
    token = bytes_.substr(begin, cursor_ - begin);
    token_line_ = body_line_;
    return true;
  }

  bool read_binary(PlyType type, PlyValue& value) {
    const std::size_t size = byte_size(type);
    if (bytes_.size() - cursor_ < size) return false;
    std::array<unsigned char, 8> raw{};
    std::memcpy(raw.data(), bytes_.data() + cursor_, size);
    cursor_ += size;
    // Values are assembled from bytes explicitly, so the host's byte order does not matter.
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::size_t shift = encoding_ == PlyEncoding::binary_little_endian ? i : size - 1 - i;
      bits |= static_cast<std::uint64_t>(raw[i]) << (8 * shift);
    }
    switch (type) {
      case PlyType::int8:
        value.integer = static_cast<std::int8_t>(bits);
        break;
      case PlyType::uint8:
        value.integer = static_cast<std::uint8_t>(bits);
        break;
      case PlyType::int16:
        value.integer = static_cast<std::int16_t>(bits);
        break;
      case PlyType::uint16:
        value.integer = static_cast<std::uint16_t>(bits);
        break;
      case PlyType::int32:
        value.integer = static_cast<std::int32_t>(bits);
        break;
      case PlyType::uint32:
        value.integer = static_cast<std::uint32_t>(bits);
        break;
      case PlyType::float32: {
        const auto narrow = static_cast<std::uint32_t>(bits);
        float real = 0.0F;
        std::memcpy(&real, &narrow, sizeof real);
        value.real = real;
        break;
      }
      case PlyType::float64:
        std::memcpy(&value.real, &bits, sizeof value.real);
        break;
    }
    return true;
  }

  // Names a value in messages; built only when a message is.
  static std::string describe(const PlyProperty& property, Role role, bool is_length) {
    if (is_length) return "list length of '" + property.name + "'";
    if (role == Role::coordinate) return "vertex coordinate";
    if (role == Role::face_indices) return "face index";
    return "property '" + property.name + "' value";
  }

  // Reads one value of `type` (the property's type or its list length type); false at the end of the data.
  bool read_value(PlyType type, PlyValue& value, const PlyProperty& property, Role role, bool is_length) {
    if (encoding_ != PlyEncoding::ascii) return read_binary(type, value);
    std::string_view token;
    if (!next_token(token)) return false;
    NumberStatus status = NumberStatus::ok;
    if (type == PlyType::float32) {
      float real = 0.0F;
      status = parse_float(token, real);
      value.real = real;
    } else if (type == PlyType::float64) {
      status = parse_double(token, value.real);
    } else {
      status = parse_integer(token, value.integer);
      long long low = 0;
      long long high = 0;
      integer_range(type, low, high);
      if (status == NumberStatus::ok && (value.integer < low || value.integer > high))
        status = NumberStatus::out_of_range;
    }
    if (status == NumberStatus::ok) return true;
    const std::string what = describe(property, role, is_length);
    if (status == NumberStatus::non_finite) fail(token_line_, what + " " + quote(token) + " is not a finite number");
    if (status == NumberStatus::out_of_range && role == Role::face_indices && !is_length) {
      fail(token_line_, "face index " + std::string(token.substr(0, 40)) + " is out of range: the file has " +
                            std::to_string(counts_.vertex_count) + " vertices");
    }
    if (status == NumberStatus::out_of_range) {
      fail(token_line_, what + " " + std::string(token.substr(0, 40)) + " is out of range for its type");
    }
    fail(token_line_, what + " " + quote(token) + " is not a number");
  }

  void walk_element(std::size_t e) {
    const PlyElement& element = elements_[e];
    for (unsigned long long item = 0; item < element.count; ++item) {
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        const Role role = roles_[e][p];
        PlyValue value;
        if (!property.is_list) {
          if (!read_value(property.type, value, property, role, false)) truncated(e, item);
          if (role == Role::coordinate && !std::isfinite(value.real)) {
            fail(value_line(),
                 "vertex coordinate " + std::to_string(value.real) + " is not a finite number" + value_place(e, item));
          }
          continue;
        }
        if (!read_value(property.count_type, value, property, role, true)) truncated(e, item);
        const long long length = value.integer;
        if (length < 0) fail(value_line(), "negative list length " + std::to_string(length) + value_place(e, item));
        if (role == Role::face_indices && length != 3) {
          fail(value_line(), "face has " + count_of(length, "vertex", "vertices") + "; only triangles are supported" +
                                 value_place(e, item));
        }
        // CGAL resizes a list to its length before reading it; a length the data cannot hold is a cut file.
        const std::size_t left = bytes_.size() - cursor_;
        const std::size_t most = encoding_ == PlyEncoding::ascii ? (left + 1) / 2 : left / byte_size(property.type);
        if (static_cast<unsigned long long>(length) > most) truncated(e, item);
        for (long long k = 0; k < length; ++k) {
          if (!read_value(property.type, value, property, role, false)) truncated(e, item);
          if (role != Role::face_indices) continue;
          if (value.integer < 0)
            fail(value_line(), "negative face index " + std::to_string(value.integer) + value_place(e, item));
          if (static_cast<unsigned long long>(value.integer) >= counts_.vertex_count) {
            fail(value_line(), "face index " + std::to_string(value.integer) + " is out of range: the file has " +
                                   std::to_string(counts_.vertex_count) + " vertices" + value_place(e, item));
          }
        }
      }
    }
  }

  std::string_view bytes_;
  const std::string& file_;
  PlyEncoding encoding_ = PlyEncoding::ascii;
  std::vector<PlyElement> elements_;
  std::vector<std::vector<Role>> roles_;
  std::size_t body_offset_ = 0;
  long header_lines_ = 0;
  std::size_t cursor_ = 0;
  long body_line_ = 0;
  long token_line_ = 0;
  SoupCounts counts_;
};

}  // namespace

SoupCounts scan_ply(std::string_view bytes, const std::string& file) { return PlyScanner(bytes, file).run(); }

}  // namespace posekit::detail
