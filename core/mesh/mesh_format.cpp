#include <algorithm>
#include <cctype>
#include <string>

#include "mesh/text_scan.hpp"
#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"

namespace posekit {

MeshFormat mesh_format_from_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".obj") return MeshFormat::obj;
  if (extension == ".off") return MeshFormat::off;
  if (extension == ".ply") return MeshFormat::ply;
  const std::string known = "posekit reads and writes .obj, .off and .ply";
  if (extension.empty()) throw InputError(file.string(), 0, "the file name has no extension; " + known);
  throw InputError(file.string(), 0, "unknown mesh format " + detail::quote(extension) + "; " + known);
}

}  // namespace posekit
