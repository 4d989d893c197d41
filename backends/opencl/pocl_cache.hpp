// A kernel-cache folder of this process's own for PoCL.
//
// PoCL keeps compiled kernels in a cache folder (POCL_CACHE_DIR, by default one per user). Test
// runs start many processes at once; sharing one folder lets a process read a kernel another one is
// still writing. So, unless the user chose a folder, each process gets a fresh one, removed when
// the process ends. Within a process the cache still serves every device after the first.
#pragma once

#include <string>

namespace posekit::opencl {

/// Sets an environment variable to a fresh folder for the lifetime of the object, unless it is
/// already set (then it does nothing).
class ScopedCacheDirectory {
 public:
  /// Creates the folder under $TMPDIR (or /tmp) as "posekit-<variable>-<pid>-XXXXXX". If that
  /// fails, the variable stays unset and PoCL falls back to its default cache.
  explicit ScopedCacheDirectory(const char* variable);
  /// Removes the folder with everything in it and unsets the variable, when this object set it.
  ~ScopedCacheDirectory();
  ScopedCacheDirectory(const ScopedCacheDirectory&) = delete;
  ScopedCacheDirectory& operator=(const ScopedCacheDirectory&) = delete;

  /// The folder this object created, or empty when it created none.
  const std::string& path() const { return path_; }

 private:
  std::string variable_;
  std::string path_;
};

/// Prepares the environment of the OpenCL runtime; call before the first OpenCL call of the
/// process (device discovery does). Gives PoCL a per-process cache folder (POCL_CACHE_DIR) unless
/// one is set; the folder lives until the process exits. Safe to call from several threads.
void prepare_opencl_environment();

}  // namespace posekit::opencl
