// An RBF field uploaded by the Vulkan backend (backends/vulkan/vulkan_field.cpp) and its value
// f(p) = sum_j w_j phi(|p - c_j|) + sum_k a_k pi_k(p), shared by rbf_evaluate.comp and
// rk45_integrate.comp. Mirrors CpuField::value_at (backends/cpu/cpu_field.cpp): the sum over
// centers first (the rbf_sum loop of backends/cpu/rbf_evaluation.cpp), then each component's
// polynomial value (pk_polynomial_value of kernel_math.h) added to it.
//
// Every invocation reads the same center at the same time, so the centers are broadcast through
// uniform buffers: PK_UNIFORM_CHUNKS bindings of PK_CENTERS_PER_CHUNK centers (64 KiB each, the
// uniform-buffer range every fp64-capable desktop device offers). Centers beyond them (fields of
// more than 12,288 centers) are read from the storage-buffer view of the same memory.
//
// Loop iterations are a budget: lavapipe ends every loop of an invocation once all its loops
// together have iterated 65,535 times. The loops over centers therefore take PK_UNROLL centers per
// iteration, the host sizes its dispatches by the iteration counts documented below
// (backends/vulkan/loop_budget.hpp), and every sum counts the centers it visited, so that a sum
// cut short is detected instead of returned.
#ifndef POSEKIT_RBF_FIELD_GLSL
#define POSEKIT_RBF_FIELD_GLSL

#include "kernel_math.glsl"

// Keep in step with backends/vulkan/shader_interface.hpp.
const uint PK_CENTERS_PER_CHUNK = 1024u;
const uint PK_UNIFORM_CHUNKS = 12u;
const uint PK_UNROLL = 8u;

// Center j: entries[2 j] = (x, y, z, t), entries[2 j + 1] = (w_x, w_y, w_z, 0).
layout(std430, set = 0, binding = 2) readonly buffer FieldCenters {
  dvec4 field_centers[];
};
// Row k: the coefficients of term k for the three components, then 0.
layout(std430, set = 0, binding = 3) readonly buffer FieldPolynomial {
  dvec4 field_polynomial[PK_POLYNOMIAL_TERMS];
};
layout(std140, set = 0, binding = 4) uniform FieldChunk {
  dvec4 entries[2u * PK_CENTERS_PER_CHUNK];
} field_chunks[PK_UNIFORM_CHUNKS];

// sum += w phi(|p - c|) for one center: the body of rbf_sum's loop.
#define PK_RBF_TERM(CENTER, WEIGHT)                                                             \
  {                                                                                             \
    const double phi = pk_phi_from_squared_distance(pk_squared_distance(p - (CENTER)));        \
    sum += phi * (WEIGHT).xyz;                                                                  \
  }
#define PK_CHUNK_TERM(J) PK_RBF_TERM(field_chunks[chunk].entries[2u * (J)], \
                                     field_chunks[chunk].entries[2u * (J) + 1u])
#define PK_STORAGE_TERM(J) PK_RBF_TERM(field_centers[2u * (J)], field_centers[2u * (J) + 1u])

// sum_j w_j phi(|p - c_j|) over the centers begin <= j < end, in the order of j; `visited` counts
// the centers summed (end - begin unless the loops were cut short). Loop iterations: at most
// (end - begin) / PK_UNROLL + 8 per uniform chunk touched + 8. These and the RK45 loop of
// rk45_integrate.comp are the only loops of the shaders.
dvec3 rbf_center_sum(dvec4 p, uint begin, uint end, out uint visited) {
  dvec3 sum = dvec3(0.0LF);
  visited = 0u;
  const uint uniform_end = min(end, PK_UNIFORM_CHUNKS * PK_CENTERS_PER_CHUNK);
  for (uint chunk = begin / PK_CENTERS_PER_CHUNK; chunk * PK_CENTERS_PER_CHUNK < uniform_end;
       ++chunk) {
    const uint chunk_begin = chunk * PK_CENTERS_PER_CHUNK;
    const uint stop = uniform_end - chunk_begin < PK_CENTERS_PER_CHUNK ? uniform_end - chunk_begin
                                                                       : PK_CENTERS_PER_CHUNK;
    uint j = max(begin, chunk_begin) - chunk_begin;
    for (; j + PK_UNROLL <= stop; j += PK_UNROLL) {
      PK_CHUNK_TERM(j) PK_CHUNK_TERM(j + 1u) PK_CHUNK_TERM(j + 2u) PK_CHUNK_TERM(j + 3u)
      PK_CHUNK_TERM(j + 4u) PK_CHUNK_TERM(j + 5u) PK_CHUNK_TERM(j + 6u) PK_CHUNK_TERM(j + 7u)
      visited += PK_UNROLL;
    }
    for (; j < stop; ++j) {
      PK_CHUNK_TERM(j)
      visited += 1u;
    }
  }
  uint j = max(begin, PK_UNIFORM_CHUNKS * PK_CENTERS_PER_CHUNK);
  for (; j + PK_UNROLL <= end; j += PK_UNROLL) {
    PK_STORAGE_TERM(j) PK_STORAGE_TERM(j + 1u) PK_STORAGE_TERM(j + 2u) PK_STORAGE_TERM(j + 3u)
    PK_STORAGE_TERM(j + 4u) PK_STORAGE_TERM(j + 5u) PK_STORAGE_TERM(j + 6u) PK_STORAGE_TERM(j + 7u)
    visited += PK_UNROLL;
  }
  for (; j < end; ++j) {
    PK_STORAGE_TERM(j)
    visited += 1u;
  }
  return sum;
}

// Mirrors pk_polynomial_value for the three components at once; written out without a loop
// (see the loop budget above).
#define PK_POLYNOMIAL_ADD(K) value += field_polynomial[K].xyz * pk_polynomial_term(K, p);
dvec3 rbf_polynomial_value(dvec4 p) {
  dvec3 value = dvec3(0.0LF);
  PK_POLYNOMIAL_ADD(0u) PK_POLYNOMIAL_ADD(1u) PK_POLYNOMIAL_ADD(2u) PK_POLYNOMIAL_ADD(3u)
  PK_POLYNOMIAL_ADD(4u) PK_POLYNOMIAL_ADD(5u) PK_POLYNOMIAL_ADD(6u) PK_POLYNOMIAL_ADD(7u)
  PK_POLYNOMIAL_ADD(8u) PK_POLYNOMIAL_ADD(9u) PK_POLYNOMIAL_ADD(10u) PK_POLYNOMIAL_ADD(11u)
  PK_POLYNOMIAL_ADD(12u) PK_POLYNOMIAL_ADD(13u) PK_POLYNOMIAL_ADD(14u)
  return value;
}

// f(p) with every center; `complete` turns false when a loop was cut short.
dvec3 rbf_field_value(dvec4 p, uint center_count, inout bool complete) {
  uint visited;
  const dvec3 sum = rbf_center_sum(p, 0u, center_count, visited);
  if (visited != center_count) complete = false;
  return sum + rbf_polynomial_value(p);
}

#endif  // POSEKIT_RBF_FIELD_GLSL
