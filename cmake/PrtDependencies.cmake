# All dependencies come from Debian packages, found through their CMake config files.
find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(Eigen3 3.3 CONFIG REQUIRED)

# MPI (Open MPI from Debian) for distributed baking, src/dist: optional, on by default when found.
find_package(MPI COMPONENTS C QUIET)
option(PRT_WITH_MPI "Distributed baking over MPI (src/dist; mpirun -np N prt bake ...)" ${MPI_C_FOUND})
if(PRT_WITH_MPI AND NOT MPI_C_FOUND)
  message(FATAL_ERROR "PRT_WITH_MPI is ON but no MPI C library was found (apt-get install libopenmpi-dev openmpi-bin)")
endif()

# Debian's OpenImageIO target lists /usr/include/opencv4, which does not exist; generation fails as
# soon as anything links it. Drop that entry.
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_inc)
  list(FILTER _oiio_inc EXCLUDE REGEX "opencv4")
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc}")
endif()

if(PRT_BUILD_GL)
  set(OpenGL_GL_PREFERENCE GLVND)
  find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
  find_package(glfw3 3.3 CONFIG REQUIRED)
endif()
if(PRT_BUILD_TESTS)
  find_package(Catch2 2 CONFIG REQUIRED)
  include(Catch)
endif()
if(PRT_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
