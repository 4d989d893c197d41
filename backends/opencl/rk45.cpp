// RK45 batch integration on an OpenCL device: one launch per chunk of particles (one chunk unless
// the particles outgrow a buffer), in which every work-item runs its particle's whole adaptive
// Dormand-Prince loop (kernels/opencl/rk45.cl).
#include "chunking.hpp"
#include "kernel_launch.hpp"
#include "opencl_operations.hpp"

#include "common/rk45_counters.hpp"
#include <posekit/error.hpp>

#include <algorithm>
#include <string>

namespace posekit::opencl {

std::vector<Rk45ParticleStats> integrate_rk45(OpenClRuntime& runtime, const OpenClField& field,
                                              Eigen::Ref<Eigen::MatrixX3d> positions,
                                              const Rk45Options& options) {
  if (field.parts().size() > 1) {
    throw DeviceError("integrate_rk45: the field's " + std::to_string(field.center_count()) +
                      " centers need " + std::to_string(field.parts().size()) +
                      " buffers on this device (at most " +
                      std::to_string(runtime.max_buffer_bytes) +
                      " bytes each), and the integration reads the whole field in one kernel; "
                      "use the cpu device for a field this large");
  }
  const Eigen::Index count = positions.rows();
  std::vector<Rk45ParticleStats> stats(static_cast<std::size_t>(count));
  const OpenClField::Part& part = field.parts().front();
  // Positions (three doubles per particle) make the larger of the two buffers.
  const Eigen::Index capacity =
      std::min(count, items_per_chunk(chunk_limits(runtime.max_buffer_bytes), 3 * sizeof(double)));
  const cl::Buffer position_buffer =
      scratch_buffer(runtime, Scratch::positions, 3 * sizeof(double) * capacity);
  const cl::Buffer stats_buffer =
      scratch_buffer(runtime, Scratch::statistics, 4 * sizeof(cl_int) * capacity);
  std::vector<cl_int> chunk_stats(static_cast<std::size_t>(4 * capacity));
  for (Eigen::Index first = 0; first < count; first += capacity) {
    const Eigen::Index rows = std::min(capacity, count - first);
    write_buffer(runtime, position_buffer, pack_columns(positions, first, rows, capacity));
    set_arguments(runtime.integrate, "pk_rk45_integrate", part.buffer, part.count, part.stride,
                  field.polynomial(), position_buffer, static_cast<int>(rows),
                  static_cast<int>(capacity), options.t_begin, options.t_end,
                  options.relative_tolerance, options.absolute_tolerance, options.initial_step,
                  options.min_step, options.max_steps, stats_buffer);
    launch(runtime, runtime.integrate, static_cast<std::size_t>(rows), runtime.integrate_group,
           "pk_rk45_integrate");
    POSEKIT_CL_CHECK(runtime.queue.enqueueReadBuffer(stats_buffer, CL_TRUE, 0,
                                                     4 * sizeof(cl_int) * rows, chunk_stats.data()),
                     "clEnqueueReadBuffer");
    read_columns(runtime, position_buffer, capacity, rows, 3, positions.data(),
                 positions.outerStride(), first, 0);
    for (Eigen::Index i = 0; i < rows; ++i) {
      stats[static_cast<std::size_t>(first + i)] =
          backends::particle_stats(&chunk_stats[static_cast<std::size_t>(4 * i)]);
    }
  }
  return stats;
}

}  // namespace posekit::opencl
