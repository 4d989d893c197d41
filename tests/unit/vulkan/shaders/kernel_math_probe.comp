// Runs single functions of shaders/kernel_math.glsl on a list of inputs, so that tests can hold
// them against the C definitions in kernel_math.h: mode 0 pk_log, mode 1 pk_pow_error_exponent,
// mode 2 the constants of kernel_constants.glsl in the order of PK_KERNEL_DOUBLE_CONSTANTS (the
// input is ignored).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "kernel_math.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Inputs {
  double inputs[];
};
layout(std430, set = 0, binding = 1) writeonly buffer Outputs {
  double outputs[];
};

layout(push_constant) uniform Push {
  uint mode;
  uint count;
} push;

const double kConstants[] = double[](
    PK_DBL_MIN, PK_LOG_LN2_HI, PK_LOG_LN2_LO, PK_LOG_LG1, PK_LOG_LG2, PK_LOG_LG3, PK_LOG_LG4,
    PK_LOG_LG5, PK_LOG_LG6, PK_LOG_LG7, PK_LOG_EXPONENT_BIAS_MAGIC,
    PK_DP_C2, PK_DP_C3, PK_DP_C4, PK_DP_C5, PK_DP_C6, PK_DP_C7,
    PK_DP_A21, PK_DP_A31, PK_DP_A32, PK_DP_A41, PK_DP_A42, PK_DP_A43,
    PK_DP_A51, PK_DP_A52, PK_DP_A53, PK_DP_A54,
    PK_DP_A61, PK_DP_A62, PK_DP_A63, PK_DP_A64, PK_DP_A65,
    PK_DP_B1, PK_DP_B3, PK_DP_B4, PK_DP_B5, PK_DP_B6,
    PK_DP_E1, PK_DP_E3, PK_DP_E4, PK_DP_E5, PK_DP_E6, PK_DP_E7,
    PK_RK45_SAFETY, PK_RK45_MIN_FACTOR, PK_RK45_MAX_FACTOR, PK_RK45_ERROR_EXPONENT,
    PK_RK45_END_STRETCH);

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  if (push.mode == 0u) {
    outputs[i] = pk_log(inputs[i]);
  } else if (push.mode == 1u) {
    outputs[i] = pk_pow_error_exponent(inputs[i]);
  } else {
    outputs[i] = i < uint(kConstants.length()) ? kConstants[i] : 0.0LF;
  }
}
