# Install rules and the exported CMake package lme_mpm:
#   cmake --install build --prefix DIR
# puts the program in DIR/bin, the library in DIR/lib, the headers in DIR/include,
# the scenes in DIR/share/lme_mpm/prm, the documentation (with the plug-in example)
# in DIR/share/doc/lme_mpm, and the package files in DIR/lib/cmake/lme_mpm, so that a
# plug-in's CMakeLists.txt needs only find_package(lme_mpm) and lme_mpm_add_plugin().
include(CMakePackageConfigHelpers)

set(LME_MPM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/lme_mpm)

install(TARGETS lme_mpm_lib lme-mpm EXPORT lme_mpmTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/lme_mpm
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/prm/ DESTINATION ${CMAKE_INSTALL_DATADIR}/lme_mpm/prm)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/doc/ DESTINATION ${CMAKE_INSTALL_DOCDIR}
        PATTERN Doxyfile EXCLUDE)
# Every scene's plot script, with the helpers they import.
file(GLOB LME_MPM_PLOT_SCRIPTS ${CMAKE_SOURCE_DIR}/scripts/plot_*.py)
install(PROGRAMS ${LME_MPM_PLOT_SCRIPTS} ${CMAKE_SOURCE_DIR}/scripts/scene_plots.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/lme_mpm/scripts)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The deal.II flavour the library links (deal_ii_setup_target's choice): a plug-in
# must link the same one, or two deal.II libraries would end up in one process.
if(CMAKE_BUILD_TYPE STREQUAL "Debug" AND DEAL_II_BUILD_TYPE MATCHES "Debug")
  set(LME_MPM_DEAL_II_FLAVOUR DEBUG)
else()
  set(LME_MPM_DEAL_II_FLAVOUR RELEASE)
endif()

install(EXPORT lme_mpmTargets NAMESPACE lme_mpm:: DESTINATION ${LME_MPM_INSTALL_CMAKEDIR})
configure_package_config_file(
  ${CMAKE_SOURCE_DIR}/cmake/lme_mpmConfig.cmake.in
  ${CMAKE_BINARY_DIR}/lme_mpmConfig.cmake
  INSTALL_DESTINATION ${LME_MPM_INSTALL_CMAKEDIR})
# Plug-ins are compiled against the headers and layout of one release series.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/lme_mpmConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/lme_mpmConfig.cmake
              ${CMAKE_BINARY_DIR}/lme_mpmConfigVersion.cmake
        DESTINATION ${LME_MPM_INSTALL_CMAKEDIR})

# cpack -G DEB in the build directory: a Debian package of the install tree.
set(CPACK_PACKAGE_NAME lme-mpm)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Explicit MPM solver for quasi-brittle fracture (LME shape functions, eigensoftening)")
set(CPACK_PACKAGE_CONTACT "lme-mpm developers")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libdeal.ii-dev (>= 9.4), libboost-program-options-dev")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_STRIP_FILES ON)
include(CPack)
