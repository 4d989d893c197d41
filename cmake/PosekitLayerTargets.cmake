# posekit_add_layer(<layer> SOURCES file... [LIBRARIES target...])
# Builds a layer of cmake/PosekitLayers.cmake as the object library posekit_<layer>: linked to the
# targets of the layers it uses (so a layer compiles with what those layers require, and no more),
# privately to the third-party LIBRARIES its own sources need (CGAL's -frounding-math, for one,
# stays with the layers that include CGAL), its objects and those libraries part of the posekit
# library.
function(posekit_add_layer layer)
  cmake_parse_arguments(arg "" "" "SOURCES;LIBRARIES" ${ARGN})
  if(NOT layer IN_LIST POSEKIT_LAYERS)
    message(FATAL_ERROR "posekit_add_layer: ${layer} is not a layer of cmake/PosekitLayers.cmake")
  endif()
  set(target posekit_${layer})
  add_library(${target} OBJECT ${arg_SOURCES})
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_include_directories(${target}
    PUBLIC ${PROJECT_SOURCE_DIR}/core/include ${PROJECT_BINARY_DIR}/generated/include
    PRIVATE ${PROJECT_SOURCE_DIR}/core ${PROJECT_SOURCE_DIR}/backends)
  target_link_libraries(${target} PUBLIC Eigen3::Eigen PRIVATE ${arg_LIBRARIES})
  foreach(used IN LISTS POSEKIT_LAYER_${layer}_USES)
    # Layers without sources (base) or not built (a GPU backend switched off) have no target.
    if(TARGET posekit_${used})
      target_link_libraries(${target} PUBLIC posekit_${used})
    endif()
  endforeach()
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  target_sources(posekit PRIVATE $<TARGET_OBJECTS:${target}>)
  target_link_libraries(posekit PRIVATE ${arg_LIBRARIES})
endfunction()
