// CHOLMOD's supernodal factorization opens OpenMP regions of its own beside the threads of the BLAS
// it calls, and an OpenMP team waits for its next region spinning before it sleeps. With few cores
// those waiting threads take the cores from the BLAS's threads and from TBB's, and the whole mesh's
// edge-space pose took half as long again with them as with the regions run on one thread, to the
// same bits (docs/interpolate.md, "Speed"). The regions are serialized only while CHOLMOD works;
// the BLAS keeps its threads.
#pragma once

namespace posekit::interpolation {

/// While one lives, the parallel regions its thread opens (CHOLMOD's, called from that thread) run on
/// one thread: the OpenMP runtime already loaded in the process, if any, has that thread's
/// max-active-levels set to 0, a setting OpenMP keeps per thread; its end restores the level it
/// found. Other threads are not touched. Does nothing where no OpenMP runtime is loaded.
class SerializedOpenMpRegions {
 public:
  SerializedOpenMpRegions();
  ~SerializedOpenMpRegions();
  SerializedOpenMpRegions(const SerializedOpenMpRegions&) = delete;
  SerializedOpenMpRegions& operator=(const SerializedOpenMpRegions&) = delete;

  /// The runtime's max-active-levels of the calling thread; -1 where no OpenMP runtime is loaded.
  static int max_active_levels();

 private:
  int levels_before_;
};

}  // namespace posekit::interpolation
