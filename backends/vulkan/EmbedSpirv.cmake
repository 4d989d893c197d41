# posekit_embed_spirv(TARGET target SOURCES shader.comp...
#                     [INCLUDE_DIRECTORIES dir...] [DEPENDS file-or-target...])
# Compiles each GLSL compute shader to SPIR-V (Vulkan 1.2) with glslangValidator at build time and
# makes it available to `target` as a generated header in the build tree: <name>.spv.h declaring
#   const uint32_t posekit_spirv_<name>[]
# (name: the file name without .comp). The header folder is added to the target's private include
# path. Dependencies on #include'd files are tracked through glslang's depfile.
function(posekit_embed_spirv)
  cmake_parse_arguments(arg "" "TARGET" "SOURCES;INCLUDE_DIRECTORIES;DEPENDS" ${ARGN})
  if(NOT POSEKIT_GLSLANG_VALIDATOR)
    message(FATAL_ERROR
            "posekit_embed_spirv: glslangValidator was not found (Debian: glslang-tools)")
  endif()
  set(output_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${output_dir})
  set(include_flags "")
  foreach(dir IN LISTS arg_INCLUDE_DIRECTORIES)
    list(APPEND include_flags "-I${dir}")
  endforeach()
  set(headers "")
  foreach(source IN LISTS arg_SOURCES)
    get_filename_component(source ${source} ABSOLUTE)
    get_filename_component(name ${source} NAME_WE)
    set(header ${output_dir}/${name}.spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${POSEKIT_GLSLANG_VALIDATOR} --quiet -V --target-env vulkan1.2 ${include_flags}
              --vn posekit_spirv_${name} --depfile ${output_dir}/${name}.spv.d
              -o ${header} ${source}
      MAIN_DEPENDENCY ${source}
      DEPENDS ${arg_DEPENDS}
      DEPFILE ${output_dir}/${name}.spv.d
      COMMENT "Compiling ${name}.comp to SPIR-V"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  # A target of its own: the custom commands live in this directory, the consuming target may
  # live in another (posekit is defined at the top level).
  add_custom_target(${arg_TARGET}_spirv DEPENDS ${headers})
  add_dependencies(${arg_TARGET} ${arg_TARGET}_spirv)
  target_include_directories(${arg_TARGET} PRIVATE ${output_dir})
endfunction()
