# All dependencies come from Debian packages, found through their CMake config files (pkg-config for
# Dear ImGui). Each package is searched for only when a module that uses it is configured
# (cmake/PrtModules.cmake): a core-only build (-DPRT_COMPONENTS=core) never looks for Embree,
# OpenImageIO, GL or MPI.
include(PrtModules)

# PRT_ENABLED_MODULES: the modules named in PRT_COMPONENTS and those they depend on.
if(PRT_COMPONENTS STREQUAL "all")
  set(_prt_requested ${PRT_MODULES})
  if(NOT PRT_BUILD_GL)
    list(REMOVE_ITEM _prt_requested render)
  endif()
else()
  set(_prt_requested ${PRT_COMPONENTS})
  foreach(m IN LISTS _prt_requested)
    if(NOT m IN_LIST PRT_MODULES)
      message(FATAL_ERROR "PRT_COMPONENTS names '${m}', which is not a prt module (${PRT_MODULES})")
    endif()
  endforeach()
endif()
prt_module_closure(PRT_ENABLED_MODULES ${_prt_requested})
message(STATUS "prt modules: ${PRT_ENABLED_MODULES}")

# MPI (Open MPI from Debian) for distributed baking, src/dist: optional, on by default when found.
if("dist" IN_LIST PRT_ENABLED_MODULES)
  find_package(MPI COMPONENTS C QUIET)
  option(PRT_WITH_MPI "Distributed baking over MPI (src/dist; mpirun -np N prt bake ...)" ${MPI_C_FOUND})
  if(PRT_WITH_MPI AND NOT MPI_C_FOUND)
    message(FATAL_ERROR "PRT_WITH_MPI is ON but no MPI C library was found (apt-get install libopenmpi-dev openmpi-bin)")
  endif()
endif()

foreach(m IN LISTS PRT_ENABLED_MODULES)
  prt_find_module_packages(find_package ${m})
endforeach()
# OpenImageIO is the image module's dlopen()ed backend (not a link dependency of prt_image).
if("image" IN_LIST PRT_ENABLED_MODULES)
  find_package(OpenImageIO CONFIG REQUIRED)
  # Debian's OpenImageIO target lists /usr/include/opencv4, which does not exist; generation fails as
  # soon as anything links it. Drop that entry.
  get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
  if(_oiio_inc)
    list(FILTER _oiio_inc EXCLUDE REGEX "opencv4")
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc}")
  endif()
endif()

# What only the executable, the tests and the benchmarks use.
if(PRT_BUILD_CLI)
  find_package(CLI11 CONFIG REQUIRED)
endif()
if(PRT_BUILD_TESTS)
  find_package(Catch2 2 CONFIG REQUIRED)
  include(Catch)
endif()
if(PRT_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
