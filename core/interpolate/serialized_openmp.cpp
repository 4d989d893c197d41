#include "interpolate/serialized_openmp.hpp"

#include <dlfcn.h>

#include <initializer_list>

namespace posekit::interpolation {
namespace {

// The runtime CHOLMOD brought in, found by its library name without loading one: linking an OpenMP
// runtime here could name another one than CHOLMOD's (Clang's libomp beside Debian's libgomp).
class OpenMpRuntime {
 public:
  OpenMpRuntime() {
    for (const char* name : {"libgomp.so.1", "libomp.so.5", "libomp.so"}) {
      void* library = dlopen(name, RTLD_LAZY | RTLD_NOLOAD);
      if (library == nullptr) continue;
      get_ = reinterpret_cast<GetLevels>(dlsym(library, "omp_get_max_active_levels"));
      set_ = reinterpret_cast<SetLevels>(dlsym(library, "omp_set_max_active_levels"));
      if (get_ != nullptr && set_ != nullptr) return;  // the reference dlopen added keeps it loaded
      get_ = nullptr;
      set_ = nullptr;
      dlclose(library);
    }
  }

  /// The calling thread's level before, or -1 without a runtime.
  int serialize() const {
    if (set_ == nullptr) return -1;
    const int before = get_();
    set_(0);
    return before;
  }

  void restore(int levels) const {
    if (set_ != nullptr) set_(levels);
  }

  int levels() const { return get_ == nullptr ? -1 : get_(); }

 private:
  using GetLevels = int (*)();
  using SetLevels = void (*)(int);
  GetLevels get_ = nullptr;
  SetLevels set_ = nullptr;
};

const OpenMpRuntime& runtime() {
  static const OpenMpRuntime instance;
  return instance;
}

}  // namespace

SerializedOpenMpRegions::SerializedOpenMpRegions() : levels_before_(runtime().serialize()) {}

SerializedOpenMpRegions::~SerializedOpenMpRegions() { runtime().restore(levels_before_); }

int SerializedOpenMpRegions::max_active_levels() { return runtime().levels(); }

}  // namespace posekit::interpolation
