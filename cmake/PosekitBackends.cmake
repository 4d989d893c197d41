# Which GPU backends to build: each when its toolchain is found (POSEKIT_<NAME>=AUTO), forced with ON
# (configure fails if the toolchain is missing) or switched off with OFF. Included from the top level
# because CUDA must be enabled in the directory that defines the posekit target.

find_package(OpenCL QUIET)
find_package(OpenCLHeaders QUIET)
find_package(OpenCLHeadersCpp QUIET)
set(opencl_found FALSE)
if(OpenCL_FOUND AND OpenCLHeadersCpp_FOUND)
  set(opencl_found TRUE)
endif()
posekit_backend_option(OPENCL opencl_found
  "the OpenCL ICD loader, headers or C++ bindings are missing (Debian: ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers)")

find_package(Vulkan QUIET COMPONENTS glslangValidator)
find_program(POSEKIT_GLSLANG_VALIDATOR glslangValidator)
set(vulkan_found FALSE)
if(Vulkan_FOUND AND POSEKIT_GLSLANG_VALIDATOR)
  set(vulkan_found TRUE)
endif()
posekit_backend_option(VULKAN vulkan_found
  "the Vulkan loader and headers or glslangValidator are missing (Debian: libvulkan-dev glslang-tools)")

include(CheckLanguage)
if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX} AND EXISTS /usr/local/cuda/bin/nvcc)
  set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc CACHE FILEPATH "CUDA compiler")
endif()
set(cuda_found FALSE)
if(NOT POSEKIT_CUDA STREQUAL "OFF")
  check_language(CUDA)
  if(CMAKE_CUDA_COMPILER)
    set(cuda_found TRUE)
  endif()
endif()
posekit_backend_option(CUDA cuda_found
  "nvcc was not found (set CMAKE_CUDA_COMPILER or install the CUDA toolkit in /usr/local/cuda)")

if(POSEKIT_BUILD_CUDA)
  if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
    # Data-centre GPUs of the last generations, plus PTX for newer ones.
    set(CMAKE_CUDA_ARCHITECTURES 80-real 90-real 90-virtual)
  endif()
  enable_language(CUDA)
  find_package(CUDAToolkit REQUIRED)
endif()
