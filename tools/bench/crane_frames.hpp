// The captured crane sequence of the shared data, as the benchmarks read it.
#pragma once

#include <posekit/mesh_io.hpp>

#include <Eigen/Core>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace posekit {

/// The 175 frames' vertices (`names` gets each file name), or an empty list with `missing` naming the
/// first file not found under `data`.
inline std::vector<Eigen::MatrixX3d> read_crane_frames(const std::filesystem::path& data, std::vector<std::string>& names,
                                                       std::string& missing) {
  std::vector<Eigen::MatrixX3d> frames;
  for (int frame = 0; frame < 175; ++frame) {
    char name[48];
    std::snprintf(name, sizeof name, "crane-sequence/crane-%04d.obj", frame);
    if (!std::filesystem::exists(data / name)) {
      missing = name;
      return {};
    }
    frames.push_back(read_mesh(data / name).vertices);
    names.push_back(std::filesystem::path(name).filename().string());
  }
  return frames;
}

}  // namespace posekit
