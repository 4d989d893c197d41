// RBF assembly: one rectangle of the block A(i, j) = phi(|y_i - c_j|), followed by the polynomial
// columns pi_k(y_i) (Device::assemble_rbf_block; backends/vulkan/rbf_assembly.cpp splits the block
// into rectangles that fit one storage buffer). Mirrors phi_column of
// backends/cpu/rbf_assembly.cpp and pk_polynomial_basis.
//
// The rectangle is column-major with a column length of 4 * row_quads (the rows rounded up to a
// multiple of 4): its first `center_columns` columns belong to the centers in `centers`, the
// remaining ones to the polynomial terms first_term, first_term + 1, ... Each invocation computes
// 4 consecutive rows of PK_COLUMNS_PER_GROUP columns and stores each column's 4 values at once:
// lavapipe writes a storage buffer lane by lane, so one dvec4 store costs about what one double
// store does. The centers come from a uniform buffer: every invocation reads the same one.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "kernel_math.glsl"

// Keep in step with backends/vulkan/shader_interface.hpp.
const uint PK_COLUMNS_PER_GROUP = 8u;
const uint PK_ASSEMBLY_CENTERS = 2048u;

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Points {
  dvec4 points[];  // (x, y, z, t), 4 * row_quads of them
};
layout(std140, set = 0, binding = 1) uniform Centers {
  dvec4 centers[PK_ASSEMBLY_CENTERS];  // one per center column
};
layout(std430, set = 0, binding = 2) writeonly buffer Block {
  dvec4 block[];  // rows 4 q .. 4 q + 3 of column j at block[j * row_quads + q]
};

layout(push_constant) uniform Push {
  uint row_quads;
  uint columns;
  uint center_columns;
  uint first_term;
} push;

double phi(dvec4 point, dvec4 center) {
  return pk_phi_from_squared_distance(pk_squared_distance(point - center));
}

void main() {
  // Invocations past the last quad compute it again without storing: no invocation leaves
  // early, which keeps control flow uniform (see rk45_integrate.comp).
  const uint quad = min(gl_GlobalInvocationID.x, push.row_quads - 1u);
  const dvec4 p0 = points[4u * quad];
  const dvec4 p1 = points[4u * quad + 1u];
  const dvec4 p2 = points[4u * quad + 2u];
  const dvec4 p3 = points[4u * quad + 3u];
  const uint first_column = gl_WorkGroupID.y * PK_COLUMNS_PER_GROUP;
  const uint last_column = min(first_column + PK_COLUMNS_PER_GROUP, push.columns);
  for (uint column = first_column; column < last_column; ++column) {
    dvec4 values;
    if (column < push.center_columns) {
      const dvec4 center = centers[column];
      values = dvec4(phi(p0, center), phi(p1, center), phi(p2, center), phi(p3, center));
    } else {
      const uint term = push.first_term + column - push.center_columns;
      values = dvec4(pk_polynomial_term(term, p0), pk_polynomial_term(term, p1),
                     pk_polynomial_term(term, p2), pk_polynomial_term(term, p3));
    }
    if (gl_GlobalInvocationID.x < push.row_quads) block[column * push.row_quads + quad] = values;
  }
}
