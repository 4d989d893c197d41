// Writing a file whole or not at all.
#pragma once

#include <filesystem>
#include <string_view>

namespace posekit {

/// Writes `bytes` to a new temporary file beside `target`, flushes it to disk, then renames it over
/// `target`, so that readers see the old file or the complete new one, never a part. On failure the
/// temporary file is removed and InputError names `target`.
void write_file_atomically(const std::filesystem::path& target, std::string_view bytes);

}  // namespace posekit
