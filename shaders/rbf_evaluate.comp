// RBF evaluation: values[i] = f(points[i]) for a batch of points, one invocation per point
// (Device::evaluate_rbf; backends/vulkan/rbf_evaluation.cpp records the dispatches). A field with
// more centers than one invocation's loop budget allows is summed in several dispatches over
// ranges of centers: the first writes, the others add, the last adds the polynomial part.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "rbf_field.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Points {
  dvec4 points[];  // (x, y, z, t)
};
layout(std430, set = 0, binding = 1) buffer Values {
  double values[];  // 3 per point
};
layout(std430, set = 0, binding = 5) writeonly buffer Diagnostics {
  uint incomplete;  // set to 1 when a sum was cut short
};

// Keep in step with EvaluationPush in backends/vulkan/shader_interface.hpp.
const uint PK_ADD_TO_VALUES = 1u;
const uint PK_ADD_POLYNOMIAL = 2u;

layout(push_constant) uniform Push {
  uint point_count;
  uint center_begin;
  uint center_end;
  uint flags;
} push;

void main() {
  // Invocations past the batch sum for the last point and do not write: every invocation of a
  // subgroup takes part in the loops over centers (see rk45_integrate.comp for why).
  const uint i = min(gl_GlobalInvocationID.x, push.point_count - 1u);
  const dvec4 p = points[i];
  uint visited;
  dvec3 value = rbf_center_sum(p, push.center_begin, push.center_end, visited);
  if (visited != push.center_end - push.center_begin) incomplete = 1u;
  if (gl_GlobalInvocationID.x >= push.point_count) return;
  if ((push.flags & PK_ADD_TO_VALUES) != 0u) {
    value = dvec3(values[3u * i], values[3u * i + 1u], values[3u * i + 2u]) + value;
  }
  if ((push.flags & PK_ADD_POLYNOMIAL) != 0u) value += rbf_polynomial_value(p);
  values[3u * i] = value.x;
  values[3u * i + 1u] = value.y;
  values[3u * i + 2u] = value.z;
}
