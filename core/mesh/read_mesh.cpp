// read_mesh: the file's bytes are checked by the structure scan of their format, then read by CGAL's
// polygon-soup reader, then CGAL's result is compared with what the scan counted and validated.
#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "mesh/mesh_file_scan.hpp"
#include "mesh/polygon_soup.hpp"
#include "mesh/text_scan.hpp"
#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"
#include "posekit/mesh_validation.hpp"

namespace posekit {
namespace {

std::string read_bytes(const std::filesystem::path& file, const std::string& name) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw InputError(name, 0, "cannot open the file: it does not exist");
  }
  if (status.type() == std::filesystem::file_type::directory) {
    throw InputError(name, 0, "cannot read the file: it is a directory");
  }
  std::ifstream stream(file, std::ios::binary);
  if (!stream) {
    throw InputError(name, 0, "cannot open the file: " + std::generic_category().message(errno));
  }
  std::string bytes;
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  while (stream) {
    const std::size_t old_size = bytes.size();
    bytes.resize(old_size + kChunk);
    stream.read(bytes.data() + old_size, static_cast<std::streamsize>(kChunk));
    bytes.resize(old_size + static_cast<std::size_t>(stream.gcount()));
  }
  if (stream.bad()) throw InputError(name, 0, "cannot read the file: " + std::generic_category().message(errno));
  return bytes;
}

// Runs one CGAL reader: its exceptions and its `false` become InputError. After a passing scan
// neither should happen; this keeps a surprise from escaping as anything else.
template <typename Read>
void run_cgal_reader(const char* format, const std::string& name, Read read) {
  bool ok = false;
  try {
    ok = read();
  } catch (const std::exception& error) {
    throw InputError(name, 0, detail::one_line(std::string("CGAL's ") + format + " reader failed: " + error.what()));
  }
  if (!ok) throw InputError(name, 0, std::string("CGAL's ") + format + " reader could not read the file");
}

void check_counts(const char* format, const std::string& name, const detail::PolygonSoup& soup,
                  std::size_t vertex_count, std::size_t face_count) {
  if (soup.points.size() != vertex_count || soup.polygons.size() != face_count) {
    throw InputError(name, 0,
                     std::string("CGAL's ") + format + " reader read " + std::to_string(soup.points.size()) +
                         " vertices and " + std::to_string(soup.polygons.size()) + " faces, but the file has " +
                         std::to_string(vertex_count) + " and " + std::to_string(face_count));
  }
}

detail::PolygonSoup read_obj(std::string text, const std::string& name) {
  const detail::ObjScan scan = detail::scan_obj(text, name);
  // CGAL skips only up to the next space after each face index: a tab there would hide the next index.
  std::replace(text.begin(), text.end(), '\t', ' ');
  std::istringstream stream(text);
  detail::PolygonSoup soup;
  run_cgal_reader("OBJ", name, [&] {
    return detail::read_obj_soup(stream, soup);
  });
  check_counts("OBJ", name, soup, scan.vertex_count, scan.face_lines.size());
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    if (soup.polygons[f].size() != 3) {
      throw InputError(name, scan.face_lines[f],
                       "CGAL's OBJ reader read " + std::to_string(soup.polygons[f].size()) +
                           " indices from this face line, which lists 3");
    }
  }
  return soup;
}

detail::PolygonSoup read_off(const std::string& text, const std::string& name) {
  const detail::SoupCounts counts = detail::scan_off(text, name);
  std::istringstream stream(text);
  detail::PolygonSoup soup;
  run_cgal_reader("OFF", name, [&] { return detail::read_off_soup(stream, soup); });
  check_counts("OFF", name, soup, counts.vertex_count, counts.face_count);
  return soup;
}

detail::PolygonSoup read_ply(const std::string& bytes, const std::string& name) {
  const detail::SoupCounts counts = detail::scan_ply(bytes, name);
  std::istringstream stream(bytes, std::ios::in | std::ios::binary);
  detail::PolygonSoup soup;
  run_cgal_reader("PLY", name, [&] {
    return detail::read_ply_soup(stream, soup);
  });
  check_counts("PLY", name, soup, counts.vertex_count, counts.face_count);
  return soup;
}

}  // namespace

Mesh read_mesh(const std::filesystem::path& file, std::vector<std::string>* warnings) {
  const std::string name = file.string();
  const MeshFormat format = mesh_format_from_extension(file);
  std::string bytes = read_bytes(file, name);
  if (bytes.empty()) throw InputError(name, 0, "the file is empty");
  if (detail::is_all_space(bytes)) throw InputError(name, 0, "the file holds only whitespace");
  // Some editors start text files with a UTF-8 byte order mark, which CGAL's text readers do not skip.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (format != MeshFormat::ply && std::string_view(bytes).substr(0, 3) == kByteOrderMark) bytes.erase(0, 3);
  detail::PolygonSoup soup;
  switch (format) {
    case MeshFormat::obj:
      soup = read_obj(std::move(bytes), name);
      break;
    case MeshFormat::off:
      soup = read_off(bytes, name);
      break;
    case MeshFormat::ply:
      soup = read_ply(bytes, name);
      break;
  }
  Mesh mesh = detail::mesh_from_soup(soup, name);
  validate_mesh(mesh, name, warnings);
  return mesh;
}

}  // namespace posekit
