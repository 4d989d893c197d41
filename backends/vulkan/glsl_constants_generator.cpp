// Build-time tool: writes every constant of kernel_math.h as GLSL, so that the compute shaders
// (which cannot include the C header) use bit-identical values. Usage: OUTPUT_FILE.
//
// Doubles are printed with 17 significant digits, which round-trips every double exactly; the
// conversion in the shader compiler is checked bit for bit by tests/unit/vulkan.
#include "common/kernel_math.h"

#include <cstdio>
#include <string>

namespace {

std::string glsl_double(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", value);
  std::string literal = text;
  // GLSL needs a '.' or an exponent before the LF suffix ("1LF" is not a double literal).
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
  return literal + "LF";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_FILE\n", argv[0]);
    return 2;
  }
  std::FILE* out = std::fopen(argv[1], "w");
  if (out == nullptr) {
    std::fprintf(stderr, "%s: cannot write %s\n", argv[0], argv[1]);
    return 1;
  }
  std::fprintf(out,
               "// Generated at build time from backends/common/kernel_math.h by "
               "glsl_constants_generator.cpp; do not edit.\n");
#define POSEKIT_PRINT_DOUBLE(name) \
  std::fprintf(out, "const double %s = %s;\n", #name, glsl_double((double)(name)).c_str());
#define POSEKIT_PRINT_WORD(name) \
  std::fprintf(out, "const int %s = %lld;\n", #name, (long long)(name));
  PK_KERNEL_DOUBLE_CONSTANTS(POSEKIT_PRINT_DOUBLE)
  PK_KERNEL_WORD_CONSTANTS(POSEKIT_PRINT_WORD)
#undef POSEKIT_PRINT_DOUBLE
#undef POSEKIT_PRINT_WORD
  const bool written = std::ferror(out) == 0;
  if (std::fclose(out) != 0 || !written) {
    std::fprintf(stderr, "%s: writing %s failed\n", argv[0], argv[1]);
    return 1;
  }
  return 0;
}
