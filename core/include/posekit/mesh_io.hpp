// Reading and writing triangle meshes and pose sets as OBJ, OFF or PLY files.
//
// Reading goes through CGAL's polygon-soup readers and keeps vertex and face order exactly as in the
// file. Every problem is an InputError whose one-line message names the file and, where the format
// has lines, the line. Writing is atomic: the output file appears whole or not at all.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "posekit/mesh.hpp"

namespace posekit {

/// The mesh file formats posekit reads and writes.
enum class MeshFormat { obj, off, ply };

/// The format named by the extension of `file`: .obj, .off or .ply in any letter case.
/// Throws InputError naming the file for any other extension, so callers can check an output name early.
MeshFormat mesh_format_from_extension(const std::filesystem::path& file);

/// Reads a triangle mesh (#V by 3 vertices, #F by 3 zero-based faces) from an OBJ, OFF or PLY file
/// (ASCII or binary PLY). Throws InputError for an unreadable or malformed file, a non-triangle face,
/// an index out of range or a non-finite coordinate; appends one-line warnings (unreferenced vertices,
/// degenerate faces) to `warnings` when it is given.
Mesh read_mesh(const std::filesystem::path& file, std::vector<std::string>* warnings = nullptr);

/// Writes `mesh` to `file`, in the format of its extension (PLY is written binary). Coordinates are
/// written with 17 significant digits, so reading the file back gives the same doubles bit for bit.
/// The data go to a temporary file in the same folder, which is then renamed over `file`; on any
/// failure the temporary file is removed, `file` is left as it was, and InputError names `file`.
/// Throws ArgumentError if a face index is outside the vertices or a coordinate is not finite.
void write_mesh(const std::filesystem::path& file, const Mesh& mesh);

/// Reads the poses of one shape: every file must hold the same number of vertices and the same face
/// list as the first. Returns one pose per file, in order, named by its file name. Throws InputError
/// naming both files and the first difference, or ArgumentError when `files` is empty.
PoseSet read_pose_set(const std::vector<std::filesystem::path>& files, std::vector<std::string>* warnings = nullptr);

/// Throws InputError (naming `name_b`, `name_a` and the first differing face, or the two vertex or
/// face counts) unless `a` and `b` have the same vertex count and identical #F by 3 face lists.
void check_same_connectivity(const Mesh& a, const std::string& name_a, const Mesh& b, const std::string& name_b);

}  // namespace posekit
