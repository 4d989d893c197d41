// Structure scans of mesh files, run before CGAL reads them.
//
// CGAL 5.5's polygon-soup readers trust their input: the OFF reader resizes its arrays to the counts of
// the header and casts face entries read as doubles to indices, the PLY reader resizes lists to counts
// read from the file and dereferences properties of unexpected types, and the OBJ reader silently
// accepts relative (negative) indices, index 0, and faces cut short by a number it cannot read.
// None of them reports a line. Each scan below walks the text the way the CGAL reader will, checks
// every record (counts, coordinates, face sizes, index ranges) and throws InputError naming the file
// and the line of the first problem, so that CGAL only ever sees well-formed data. The scans check,
// they do not build the mesh: CGAL does that.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace posekit::detail {

/// What an accepted OBJ file holds, to check CGAL's result against.
struct ObjScan {
  std::size_t vertex_count = 0;  ///< number of 'v' lines
  std::vector<long> face_lines;  ///< 1-based line of each 'f' line, in order
};

/// What an accepted OFF or PLY file holds, to check CGAL's result against.
struct SoupCounts {
  std::size_t vertex_count = 0;
  std::size_t face_count = 0;
};

/// Checks an OBJ text (read from `file`); throws InputError at the first problem.
ObjScan scan_obj(std::string_view text, const std::string& file);

/// Checks an ASCII OFF text (read from `file`); throws InputError at the first problem.
SoupCounts scan_off(std::string_view text, const std::string& file);

/// Checks an ASCII or binary PLY file's bytes (read from `file`); throws InputError at the first problem.
SoupCounts scan_ply(std::string_view bytes, const std::string& file);

}  // namespace posekit::detail
