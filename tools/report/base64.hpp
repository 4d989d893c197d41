// Base64 (RFC 4648, with padding): how a report carries binary arrays inside its JSON.
#pragma once

#include <string>
#include <type_traits>
#include <string_view>
#include <vector>

namespace posekit::report {

/// The base64 text of `bytes`.
std::string base64(std::string_view bytes);

/// The base64 text of the bytes of `values` as they lie in memory: little endian on every host posekit
/// builds for (x86-64, AArch64), which is what the report's reader expects.
template <typename T>
std::string base64_of(const std::vector<T>& values) {
  static_assert(std::is_arithmetic_v<T>);
  return base64(std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

}  // namespace posekit::report
