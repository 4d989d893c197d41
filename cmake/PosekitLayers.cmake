# The layers of the library, lowest first. For each: the folders of its sources and internal headers,
# its public headers (core/include/posekit/<name>.hpp), the layers it uses directly, the layers
# allowed to include its internal headers (otherwise internals stay inside their layer), and the
# third-party header folders it CONFINES (no other layer includes them).
# One definition, two readers: posekit_add_layer() links the target of each layer to the targets of
# the layers it uses, and tests/layers checks every #include of the tree against the same table.

set(POSEKIT_LAYERS
  base cgal mesh geometry device backend_common cpu opencl vulkan cuda backends demo interpolate correct blend)

# The error type every layer throws; header only.
set(POSEKIT_LAYER_base_HEADERS error)

# Everything that includes CGAL, behind CGAL-free internal headers: the mesh readers and writers,
# exact face tests, the nearest point on a triangle, ARAP. CONFINES: third-party headers no other
# layer includes.
set(POSEKIT_LAYER_cgal_FOLDERS core/cgal)
set(POSEKIT_LAYER_cgal_USES base)
set(POSEKIT_LAYER_cgal_INTERNALS_FOR mesh geometry correct)
set(POSEKIT_LAYER_cgal_CONFINES CGAL/)

set(POSEKIT_LAYER_mesh_FOLDERS core/mesh)
set(POSEKIT_LAYER_mesh_HEADERS mesh mesh_io mesh_validation integer_list submesh atomic_file)
set(POSEKIT_LAYER_mesh_USES base cgal)

set(POSEKIT_LAYER_geometry_FOLDERS core/geometry)
set(POSEKIT_LAYER_geometry_HEADERS
  geometry topology as_rigid_as_possible face_deformation rigid_motion self_intersections
  self_intersection_tracker vertex_regions winding_numbers)
set(POSEKIT_LAYER_geometry_USES mesh)

# The compute interface and the registry that finds backends; backends register through
# device/backend_factory.hpp.
set(POSEKIT_LAYER_device_FOLDERS core/device)
set(POSEKIT_LAYER_device_HEADERS device device_registry)
set(POSEKIT_LAYER_device_USES base)
set(POSEKIT_LAYER_device_INTERNALS_FOR cpu opencl vulkan cuda backends)

set(POSEKIT_LAYER_backend_common_FOLDERS backends/common)
set(POSEKIT_LAYER_backend_common_USES device)
set(POSEKIT_LAYER_backend_common_INTERNALS_FOR cpu opencl vulkan cuda)

set(POSEKIT_LAYER_cpu_FOLDERS backends/cpu)
set(POSEKIT_LAYER_cpu_HEADERS cpu_device)
set(POSEKIT_LAYER_cpu_USES device backend_common)

set(POSEKIT_LAYER_opencl_FOLDERS backends/opencl kernels/opencl)
set(POSEKIT_LAYER_opencl_USES device backend_common)

set(POSEKIT_LAYER_vulkan_FOLDERS backends/vulkan shaders)
set(POSEKIT_LAYER_vulkan_USES device backend_common)

set(POSEKIT_LAYER_cuda_FOLDERS backends/cuda kernels/cuda)
set(POSEKIT_LAYER_cuda_USES device backend_common)

# The list of built-in backends the registry offers.
set(POSEKIT_LAYER_backends_FOLDERS backends)
set(POSEKIT_LAYER_backends_USES cpu opencl vulkan cuda)

set(POSEKIT_LAYER_demo_FOLDERS core/demo)
set(POSEKIT_LAYER_demo_HEADERS demo_shape)
set(POSEKIT_LAYER_demo_USES mesh)

set(POSEKIT_LAYER_interpolate_FOLDERS core/interpolate)
set(POSEKIT_LAYER_interpolate_HEADERS edge_space interpolate interpolation_error rigid_segmentation)
set(POSEKIT_LAYER_interpolate_USES geometry)
set(POSEKIT_LAYER_interpolate_CONFINES Eigen/CholmodSupport cholmod)

set(POSEKIT_LAYER_correct_FOLDERS core/correct)
set(POSEKIT_LAYER_correct_HEADERS correct correct_sequence rbf_fitting poisson_interpolation)
set(POSEKIT_LAYER_correct_USES geometry device interpolate)

set(POSEKIT_LAYER_blend_FOLDERS core/blend)
set(POSEKIT_LAYER_blend_HEADERS
  blend_dictionary blend_files blended_deformation feature_correspondence laplace_beltrami
  partial_registration rotation_clusters skinning_decomposition)
set(POSEKIT_LAYER_blend_USES geometry)

# posekit_layer_closure(<out-var> <layer>): the layer and every layer it uses, directly or not.
function(posekit_layer_closure out layer)
  set(seen ${layer})
  set(pending ${layer})
  while(pending)
    list(POP_FRONT pending current)
    foreach(used IN LISTS POSEKIT_LAYER_${current}_USES)
      if(NOT used IN_LIST seen)
        list(APPEND seen ${used})
        list(APPEND pending ${used})
      endif()
    endforeach()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()
