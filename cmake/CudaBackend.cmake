# The CUDA backend (src/backend/cuda/, docs/cuda-backend.md). Included by the top-level
# CMakeLists.txt at file scope (enable_language may not run inside a function), after the deme
# target exists.
#
# DEME_ENABLE_CUDA: AUTO (default) builds the backend where find_package(CUDAToolkit) finds nvcc and
# NVRTC; ON requires them; OFF never builds it. Without the backend, src/backend/cuda/ contributes
# only CudaUnavailable.cpp, which answers "no GPU" to queries and throws deme::Error from the rest.
#
# With it: the ahead-of-time parts (src/backend/cuda/*.cu: CUB sorts, scans, reductions) are built by
# nvcc for CMAKE_CUDA_ARCHITECTURES (default 90); kernels in src/backend/cuda/kernels/ are NOT built
# here but embedded as text (cmake/EmbedSources.cmake) and compiled by NVRTC at run time. The library
# links the static CUDA runtime and NVRTC, never the driver library (libcuda.so), which the runtime
# loads itself when first needed: the library and its tests start on machines without a GPU driver.

set(DEME_ENABLE_CUDA AUTO CACHE STRING
    "Build the CUDA backend: AUTO (where a CUDA toolkit with nvcc and NVRTC is found), ON or OFF")
set_property(CACHE DEME_ENABLE_CUDA PROPERTY STRINGS AUTO ON OFF)

set(deme_cuda_dir ${PROJECT_SOURCE_DIR}/src/backend/cuda)
string(TOUPPER "${DEME_ENABLE_CUDA}" deme_cuda_mode)
set(DEME_CUDA_ENABLED OFF)

if(deme_cuda_mode STREQUAL "AUTO" OR DEME_ENABLE_CUDA)
  if(deme_cuda_mode STREQUAL "AUTO")
    find_package(CUDAToolkit 12.0 QUIET)
  else()
    find_package(CUDAToolkit 12.0 REQUIRED)
  endif()
  # 12.0: the runtime's library API (cudaLibraryLoadData) that loads NVRTC's images.
  if(CUDAToolkit_FOUND AND CUDAToolkit_NVCC_EXECUTABLE AND TARGET CUDA::nvrtc AND TARGET CUDA::cudart_static)
    set(DEME_CUDA_ENABLED ON)
  elseif(NOT deme_cuda_mode STREQUAL "AUTO")
    message(FATAL_ERROR "DEME_ENABLE_CUDA=${DEME_ENABLE_CUDA}, but the CUDA toolkit found lacks nvcc or NVRTC")
  endif()
endif()

if(DEME_CUDA_ENABLED)
  # The toolkit's nvcc (it may not be on PATH), with the C++ compiler of the rest of the library.
  if(NOT DEFINED CMAKE_CUDA_COMPILER)
    set(CMAKE_CUDA_COMPILER ${CUDAToolkit_NVCC_EXECUTABLE})
  endif()
  if(NOT DEFINED CMAKE_CUDA_HOST_COMPILER)
    set(CMAKE_CUDA_HOST_COMPILER ${CMAKE_CXX_COMPILER})
  endif()
  # Hopper by default (the machines this engine is tuned on); its PTX also runs on newer GPUs.
  if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
    set(CMAKE_CUDA_ARCHITECTURES 90 CACHE STRING "GPU architectures of the ahead-of-time CUDA code")
  endif()
  enable_language(CUDA)
  message(STATUS "DEME: CUDA backend on (CUDA ${CUDAToolkit_VERSION}, architectures ${CMAKE_CUDA_ARCHITECTURES})")

  # The oldest architecture built, which a GPU must at least have (numbers like 90, 90a, 90-real);
  # 0 (no check) for "native", "all" and the like.
  set(deme_cuda_min_arch 0)
  foreach(arch IN LISTS CMAKE_CUDA_ARCHITECTURES)
    if(arch MATCHES "^([0-9]+)")
      if(deme_cuda_min_arch EQUAL 0 OR CMAKE_MATCH_1 LESS deme_cuda_min_arch)
        set(deme_cuda_min_arch ${CMAKE_MATCH_1})
      endif()
    else()
      set(deme_cuda_min_arch 0)
      break()
    endif()
  endforeach()

  file(GLOB deme_cuda_sources CONFIGURE_DEPENDS ${deme_cuda_dir}/*.cpp ${deme_cuda_dir}/*.cu)
  list(REMOVE_ITEM deme_cuda_sources ${deme_cuda_dir}/CudaUnavailable.cpp)
  target_sources(deme PRIVATE ${deme_cuda_sources})
  target_compile_definitions(deme PRIVATE DEME_HAS_CUDA=1)
  set(DEME_CUDA_BUILT ON)  # tests/CMakeLists.txt: the white-box GPU tests link the backend's classes
  set_source_files_properties(${deme_cuda_dir}/Device.cpp PROPERTIES
    COMPILE_DEFINITIONS DEME_CUDA_MIN_ARCH=${deme_cuda_min_arch})
  set_target_properties(deme PROPERTIES
    # The target exists before CUDA is enabled, so it did not pick these up from the variables.
    CUDA_ARCHITECTURES "${CMAKE_CUDA_ARCHITECTURES}"
    CUDA_STANDARD 17
    CUDA_STANDARD_REQUIRED ON
    # cudart_static is linked below, explicitly, so that consumers of the installed package get it too.
    CUDA_RUNTIME_LIBRARY None)
  # The static runtime dlopens libcuda.so.1 itself; NVRTC needs no driver at all. NVRTC is loaded
  # when the backend first compiles (backend/cuda/NvrtcLibrary.cpp), not linked: linked, its library
  # took 28 MB of resident memory in every process, CPU runs included. Its headers only here.
  get_target_property(deme_nvrtc_includes CUDA::nvrtc INTERFACE_INCLUDE_DIRECTORIES)
  if(deme_nvrtc_includes)
    target_include_directories(deme PRIVATE ${deme_nvrtc_includes})
  endif()
  target_link_libraries(deme PRIVATE CUDA::cudart_static ${CMAKE_DL_LIBS})
  set(deme_nvrtc_defs DEME_NVRTC_SONAME="libnvrtc.so.${CUDAToolkit_VERSION_MAJOR}")
  if(CUDA_nvrtc_LIBRARY)
    file(REAL_PATH "${CUDA_nvrtc_LIBRARY}" deme_nvrtc_path)
    list(APPEND deme_nvrtc_defs DEME_NVRTC_LIBRARY="${deme_nvrtc_path}")
  endif()
  set_source_files_properties(${deme_cuda_dir}/NvrtcLibrary.cpp PROPERTIES COMPILE_DEFINITIONS "${deme_nvrtc_defs}")
else()
  if(deme_cuda_mode STREQUAL "AUTO")
    message(STATUS "DEME: CUDA backend off (no CUDA toolkit >= 12.0 with nvcc and NVRTC found)")
  else()
    message(STATUS "DEME: CUDA backend off (DEME_ENABLE_CUDA=${DEME_ENABLE_CUDA})")
  endif()
  target_sources(deme PRIVATE ${deme_cuda_dir}/CudaUnavailable.cpp)
endif()
