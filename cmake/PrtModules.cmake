# The table of prt's library modules: which prt modules each one links (public or private) and which
# third-party packages it needs. It is the one place both the build (src/CMakeLists.txt: which modules
# to configure, which packages to find) and the installed prtConfig.cmake (which components to load,
# which dependencies to find) read; prt_check_module_links keeps it equal to the targets' real links.
#
# A module's list names only its direct prt dependencies; prt_module_closure adds the rest. PRT_MODULES
# lists every module after the modules it depends on (checked below): the order in which the build adds
# them and prtConfig.cmake loads them.

set(PRT_MODULES core dist image light mesh unwrap trace camera transfer brdf shade bake lightmap compress pipeline
    reference render probes)

set(PRT_MODULE_DEPS_core "")
set(PRT_MODULE_DEPS_dist core)
set(PRT_MODULE_DEPS_image core)
set(PRT_MODULE_DEPS_light core image)
set(PRT_MODULE_DEPS_mesh core image)
set(PRT_MODULE_DEPS_unwrap core mesh)
set(PRT_MODULE_DEPS_trace core mesh)
set(PRT_MODULE_DEPS_camera core mesh)
set(PRT_MODULE_DEPS_transfer core)
set(PRT_MODULE_DEPS_shade core transfer brdf light mesh trace)
set(PRT_MODULE_DEPS_brdf core)
set(PRT_MODULE_DEPS_bake core dist mesh transfer brdf trace)
set(PRT_MODULE_DEPS_lightmap core mesh transfer bake trace shade light image unwrap)
set(PRT_MODULE_DEPS_compress core transfer brdf shade light mesh)
set(PRT_MODULE_DEPS_pipeline core mesh transfer bake compress shade)
set(PRT_MODULE_DEPS_reference core dist mesh trace light camera image brdf)
set(PRT_MODULE_DEPS_render core camera image light mesh transfer brdf shade compress)
set(PRT_MODULE_DEPS_probes core dist mesh light trace bake transfer image)

set(_prt_seen "")
foreach(_prt_module IN LISTS PRT_MODULES)
  foreach(_prt_dep IN LISTS PRT_MODULE_DEPS_${_prt_module})
    if(NOT _prt_dep IN_LIST _prt_seen)
      message(FATAL_ERROR "PrtModules.cmake: ${_prt_module} depends on ${_prt_dep}, which PRT_MODULES lists after it")
    endif()
  endforeach()
  list(APPEND _prt_seen ${_prt_module})
endforeach()

# Third-party packages per module, each found by prt_find_module_packages below. Header-only packages
# used privately count too: a static library's private links still reach its users' link line.
set(PRT_MODULE_PACKAGES_core Threads glm)
set(PRT_MODULE_PACKAGES_dist "")          # MPI, when PRT_WITH_MPI (prt_find_module_packages)
set(PRT_MODULE_PACKAGES_image "")         # OpenImageIO only in the dlopen()ed backend module
set(PRT_MODULE_PACKAGES_light nlohmann_json)
set(PRT_MODULE_PACKAGES_mesh tinyobjloader TinyGLTF nlohmann_json draco meshoptimizer)
set(PRT_MODULE_PACKAGES_unwrap Eigen3)
set(PRT_MODULE_PACKAGES_trace embree)
set(PRT_MODULE_PACKAGES_camera "")
set(PRT_MODULE_PACKAGES_transfer nlohmann_json)
set(PRT_MODULE_PACKAGES_shade "")
set(PRT_MODULE_PACKAGES_brdf nlohmann_json)
set(PRT_MODULE_PACKAGES_bake nlohmann_json)
set(PRT_MODULE_PACKAGES_lightmap nlohmann_json Eigen3)
set(PRT_MODULE_PACKAGES_compress Eigen3)
set(PRT_MODULE_PACKAGES_pipeline "")
set(PRT_MODULE_PACKAGES_reference "")
set(PRT_MODULE_PACKAGES_render OpenGL glfw3 imgui)
set(PRT_MODULE_PACKAGES_probes nlohmann_json)

# How each package is found (arguments after the name).
set(PRT_PACKAGE_ARGS_Threads "")
set(PRT_PACKAGE_ARGS_glm CONFIG)
set(PRT_PACKAGE_ARGS_nlohmann_json 3 CONFIG)
set(PRT_PACKAGE_ARGS_tinyobjloader CONFIG)
set(PRT_PACKAGE_ARGS_TinyGLTF CONFIG)
set(PRT_PACKAGE_ARGS_draco CONFIG)
set(PRT_PACKAGE_ARGS_meshoptimizer CONFIG)
set(PRT_PACKAGE_ARGS_embree 3 CONFIG)
set(PRT_PACKAGE_ARGS_Eigen3 3.3 CONFIG)
set(PRT_PACKAGE_ARGS_OpenGL COMPONENTS OpenGL EGL)
set(OpenGL_GL_PREFERENCE GLVND)
set(PRT_PACKAGE_ARGS_glfw3 3.3 CONFIG)
set(PRT_PACKAGE_ARGS_MPI COMPONENTS C)

# prt_module_closure(OUT modules...): the modules named and every module they depend on, in the
# order of PRT_MODULES (dependencies first).
function(prt_module_closure out)
  set(wanted ${ARGN})
  set(grew TRUE)
  while(grew)
    set(grew FALSE)
    foreach(m IN LISTS wanted)
      foreach(d IN LISTS PRT_MODULE_DEPS_${m})
        if(NOT d IN_LIST wanted)
          list(APPEND wanted ${d})
          set(grew TRUE)
        endif()
      endforeach()
    endforeach()
  endwhile()
  set(ordered "")
  foreach(m IN LISTS PRT_MODULES)
    if(m IN_LIST wanted)
      list(APPEND ordered ${m})
    endif()
  endforeach()
  set(${out} ${ordered} PARENT_SCOPE)
endfunction()

# prt_find_module_packages(FINDER module): finds the module's third-party packages with FINDER
# (find_package with REQUIRED in the build, find_dependency in prtConfig.cmake), each package once.
# Imported targets are global (CMAKE_FIND_PACKAGE_TARGETS_GLOBAL), so any module may link them.
macro(prt_find_module_packages finder module)
  set(_prt_packages ${PRT_MODULE_PACKAGES_${module}})
  if("${module}" STREQUAL "dist" AND PRT_WITH_MPI)
    list(APPEND _prt_packages MPI)
  endif()
  foreach(_prt_package IN LISTS _prt_packages)
    if(_prt_package STREQUAL "imgui")
      # Debian's libimgui-dev has no CMake config: pkg-config (it also brings libstb).
      if(NOT TARGET PkgConfig::PRT_IMGUI)
        find_package(PkgConfig REQUIRED)
        pkg_check_modules(PRT_IMGUI REQUIRED IMPORTED_TARGET GLOBAL imgui)
      endif()
    elseif(NOT _prt_found_${_prt_package})
      if("${finder}" STREQUAL "find_package")
        find_package(${_prt_package} ${PRT_PACKAGE_ARGS_${_prt_package}} REQUIRED)
      else()
        get_property(_prt_languages GLOBAL PROPERTY ENABLED_LANGUAGES)
        if(_prt_package STREQUAL "MPI" AND NOT "C" IN_LIST _prt_languages)
          enable_language(C)  # FindMPI's C component (prt_dist links MPI::MPI_C) needs the C language
        endif()
        find_dependency(${_prt_package} ${PRT_PACKAGE_ARGS_${_prt_package}})
      endif()
      set(_prt_found_${_prt_package} TRUE)
    endif()
  endforeach()
endmacro()

# prt_check_module_links(module): fails the configure if the target prt_<module> links a prt module
# that the table above does not list for it.
function(prt_check_module_links module)
  get_target_property(links prt_${module} LINK_LIBRARIES)
  foreach(link IN LISTS links)
    if(link MATCHES "^prt_([a-z]+)$" AND NOT link STREQUAL "prt_options")
      if(NOT CMAKE_MATCH_1 IN_LIST PRT_MODULE_DEPS_${module})
        message(FATAL_ERROR "prt_${module} links ${link}, which cmake/PrtModules.cmake does not list for it")
      endif()
    endif()
  endforeach()
endfunction()
