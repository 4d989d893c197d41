#include <tbb/parallel_for.h>

#include <exception>
#include <string>
#include <vector>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"

namespace posekit {

PoseSet read_pose_set(const std::vector<std::filesystem::path>& files, std::vector<std::string>* warnings) {
  if (files.empty()) throw ArgumentError("read_pose_set: files is empty; a pose set needs at least one file");
  const std::size_t count = files.size();
  // Files are read in parallel; errors and warnings are then reported in file order, as a serial
  // read would report them.
  std::vector<Mesh> meshes(count);
  std::vector<std::vector<std::string>> file_warnings(count);
  std::vector<std::exception_ptr> errors(count);
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) {
    try {
      meshes[i] = read_mesh(files[i], &file_warnings[i]);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (std::size_t i = 0; i < count; ++i) {
    if (errors[i]) std::rethrow_exception(errors[i]);
  }

  for (std::size_t i = 1; i < count; ++i) {
    check_same_connectivity(meshes.front(), files.front().string(), meshes[i], files[i].string());
  }

  PoseSet poses(std::move(meshes.front().faces));
  for (std::size_t i = 0; i < count; ++i) {
    if (warnings != nullptr) warnings->insert(warnings->end(), file_warnings[i].begin(), file_warnings[i].end());
    poses.add_pose(std::move(meshes[i].vertices), files[i].filename().string());
  }
  return poses;
}

}  // namespace posekit
