// Text files of integers: vertex index lists, per-vertex or per-face labels.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace posekit {

/// The integers of a text file in file order, separated by white space, '#' starting a comment that
/// runs to the end of its line. Each must lie in [lowest, end); `what` names one value in errors
/// ("vertex index"). Throws InputError naming the file and the line of the first bad word.
std::vector<int> read_integer_list(const std::filesystem::path& file, const std::string& what, int lowest, int end);

}  // namespace posekit
