# Installs prt as a CMake package: one component per configured module (prt::<module>, its headers
# under include/prt/<module>/), the image module's OpenImageIO backend, the `prt` executable when built,
# and prtConfig.cmake, which loads the components asked for (find_package(prt COMPONENTS core light))
# with the modules they depend on and finds only those modules' third-party packages.
#   cmake --install build --prefix /opt/prt
# Headers include each other as "<module>/<file>.h", so include/prt is on the users' include path too;
# users may write #include <prt/sh/basis.h> or #include <sh/basis.h>.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(PRT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/prt)

foreach(module IN LISTS PRT_ENABLED_MODULES)
  install(TARGETS prt_${module} EXPORT prt_${module}_targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} ${CMAKE_INSTALL_INCLUDEDIR}/prt)
  set(folders ${module})
  if(module STREQUAL "core")
    list(APPEND folders sh)
  endif()
  foreach(folder IN LISTS folders)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prt/${folder}
            FILES_MATCHING PATTERN "*.h")
  endforeach()
  install(EXPORT prt_${module}_targets NAMESPACE prt:: DESTINATION ${PRT_INSTALL_CMAKEDIR}
          FILE prt_${module}Targets.cmake)
endforeach()
if(TARGET prt_image_oiio)
  install(TARGETS prt_image_oiio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
if(TARGET prt)
  install(TARGETS prt RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(PRT_INSTALLED_MODULES ${PRT_ENABLED_MODULES})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/prtConfig.cmake.in
  ${PROJECT_BINARY_DIR}/prtConfig.cmake INSTALL_DESTINATION ${PRT_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/prtConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/prtConfig.cmake ${PROJECT_BINARY_DIR}/prtConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/PrtModules.cmake
        DESTINATION ${PRT_INSTALL_CMAKEDIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/prt)
