// What the host code and the GLSL shaders in <root>/shaders agree on: work-group sizes, binding
// numbers, the layout of an uploaded field and the push-constant blocks. Each value names the
// shader declaration it must match.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace posekit::vulkan {

/// local_size_x of every shader.
constexpr std::uint32_t kWorkGroupSize = 64;

/// rbf_assemble.comp: PK_COLUMNS_PER_GROUP, the columns one work group covers; rows per
/// invocation (a dvec4 of one column); PK_ASSEMBLY_CENTERS, the centers of its uniform buffer.
constexpr std::uint32_t kAssemblyColumnsPerGroup = 8;
constexpr std::uint32_t kAssemblyRowsPerInvocation = 4;
constexpr std::uint32_t kAssemblyCenters = 2048;
constexpr std::uint32_t kAssemblyCenterBytes = kAssemblyCenters * 4 * sizeof(double);

/// rbf_field.glsl: PK_CENTERS_PER_CHUNK centers of 64 bytes (center dvec4, weight dvec4) per
/// uniform buffer, and PK_UNIFORM_CHUNKS such buffers; further centers are read from storage.
constexpr std::uint32_t kCentersPerChunk = 1024;
constexpr std::uint32_t kUniformChunks = 12;
constexpr std::uint32_t kFieldCenterBytes = 64;
constexpr std::uint32_t kChunkBytes = kCentersPerChunk * kFieldCenterBytes;

/// rbf_field.glsl: PK_UNROLL, centers per iteration of the loops over centers.
constexpr std::uint32_t kCentersPerIteration = 8;

/// Bindings of rbf_evaluate.comp and rk45_integrate.comp (set 0).
enum FieldBinding : std::uint32_t {
  kInputBinding = 0,        ///< points (evaluation) or particle states (RK45)
  kOutputBinding = 1,       ///< values (evaluation only)
  kCentersBinding = 2,      ///< FieldCenters: every center as storage
  kPolynomialBinding = 3,   ///< FieldPolynomial: 15 dvec4
  kChunksBinding = 4,       ///< FieldChunk[kUniformChunks]
  kDiagnosticsBinding = 5,  ///< Diagnostics (evaluation only): a uint set when a sum was cut short
};

/// Bindings of rbf_assemble.comp (set 0).
enum AssemblyBinding : std::uint32_t {
  kAssemblyPointsBinding = 0,
  kAssemblyCentersBinding = 1,
  kAssemblyBlockBinding = 2,
};

/// rbf_assemble.comp's push constants.
struct AssemblyPush {
  std::uint32_t row_quads;
  std::uint32_t columns;
  std::uint32_t center_columns;
  std::uint32_t first_term;
};

/// rbf_evaluate.comp's push constants and flags (PK_ADD_TO_VALUES, PK_ADD_POLYNOMIAL).
struct EvaluationPush {
  std::uint32_t point_count;
  std::uint32_t center_begin;
  std::uint32_t center_end;
  std::uint32_t flags;
};
constexpr std::uint32_t kAddToValues = 1;
constexpr std::uint32_t kAddPolynomial = 2;

/// rk45_integrate.comp's push constants (std430: the doubles first, then the 32-bit words).
struct Rk45Push {
  double t_end;
  double direction;
  double relative_tolerance;
  double absolute_tolerance;
  double min_step;
  std::int32_t max_steps;
  std::uint32_t particle_count;
  std::uint32_t center_count;
  std::uint32_t steps_per_round;
};

static_assert(std::is_standard_layout_v<Rk45Push> && sizeof(Rk45Push) <= 128 &&
                  offsetof(Rk45Push, max_steps) == 40 && offsetof(Rk45Push, steps_per_round) == 52,
              "Rk45Push must match the std430 push-constant block of rk45_integrate.comp");

/// rk45_integrate.comp's Rk45State: one particle between rounds (std430, 96 bytes).
struct Rk45State {
  double position_time[4];   ///< x, y, z, t
  double k1_step[4];         ///< k1, the controller's next trial step h
  std::int32_t counters[4];  ///< accepted, rejected, field evaluations, status
  std::int32_t flags[4];     ///< previous attempt rejected, a field sum was cut short, 0, 0
};

static_assert(sizeof(Rk45State) == 96, "Rk45State must match rk45_integrate.comp");

}  // namespace posekit::vulkan
