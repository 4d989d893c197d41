#include "pocl_cache.hpp"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace posekit::opencl {

ScopedCacheDirectory::ScopedCacheDirectory(const char* variable) : variable_(variable) {
  if (std::getenv(variable) != nullptr) return;
  const char* temporary = std::getenv("TMPDIR");
  std::string pattern = (temporary != nullptr && *temporary != '\0') ? temporary : "/tmp";
  std::string name = variable;
  for (char& c : name) c = c == '_' ? '-' : static_cast<char>(std::tolower(c));
  pattern += "/posekit-" + name + "-" + std::to_string(::getpid()) + "-XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (::mkdtemp(buffer.data()) == nullptr) return;
  path_ = buffer.data();
  if (::setenv(variable, path_.c_str(), 1) != 0) {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
    path_.clear();
  }
}

ScopedCacheDirectory::~ScopedCacheDirectory() {
  if (path_.empty()) return;
  // Unset only while the variable still names our folder: someone may have changed it since.
  const char* current = std::getenv(variable_.c_str());
  if (current != nullptr && path_ == current) ::unsetenv(variable_.c_str());
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

void prepare_opencl_environment() {
  // Constructed once, on the first call; destroyed at exit, after the runtime's last compilation.
  static const ScopedCacheDirectory pocl_cache("POCL_CACHE_DIR");
  (void)pocl_cache;
}

}  // namespace posekit::opencl
