# Writes a C++ source that holds the OpenCL program text: kernel_math.h followed by the .cl files,
# each as a raw string literal behind a #line directive, so that the compiler's build log names
# the original file and line. Run as
#   cmake -DOUTPUT=file.cpp -DHEADER=opencl_program_source.hpp -DSOURCES="a;b;c"
#         -P embed_kernel_sources.cmake
# (HEADER: the declaring header, by absolute path).
if(NOT OUTPUT OR NOT HEADER OR NOT SOURCES)
  message(FATAL_ERROR "embed_kernel_sources.cmake needs OUTPUT, HEADER and SOURCES")
endif()

set(delimiter "pkcl")
set(body "")
foreach(source IN LISTS SOURCES)
  file(READ "${source}" text)
  string(FIND "${text}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${source} contains the raw-string delimiter )${delimiter}\"")
  endif()
  get_filename_component(name "${source}" NAME)
  string(APPEND body "    R\"${delimiter}(#line 1 \"${name}\"\n${text}\n)${delimiter}\"\n")
endforeach()

set(content "// Generated from kernel_math.h and kernels/opencl/*.cl by
// backends/opencl/embed_kernel_sources.cmake at build time. Do not edit.
#include \"${HEADER}\"

namespace posekit::opencl {

const char* program_source() {
  return
${body}    ;
}

}  // namespace posekit::opencl
")

# Rewrite only when the text changed, so that an unchanged kernel does not rebuild the library.
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/PosekitWriteIfChanged.cmake)
posekit_write_if_changed("${OUTPUT}" "${content}")
