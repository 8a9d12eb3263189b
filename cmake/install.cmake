# Installation: `cmake --install BUILD [--prefix PREFIX]` installs graspcd as a library for any
# MuJoCo 2.2 program (README.md, "Using graspcd in your MuJoCo program"):
#   PREFIX/include/graspcd/core/*.h, PREFIX/include/graspcd/bridge/*.h (included as "core/..." and
#     "bridge/...": the targets put PREFIX/include/graspcd on the include path)
#   PREFIX/lib/libgraspcd_core.a     graspcd::core    pure geometry: Eigen, qhull; no MuJoCo
#   PREFIX/lib/libgraspcd_bridge.a   graspcd::mujoco  the MuJoCo bridge: graspcd::core + MuJoCo
#   PREFIX/lib/cmake/graspcd/        graspcdConfig.cmake, its version file and the targets
# so that `find_package(graspcd 0.1 REQUIRED)` gives the two targets. graspcd_io, graspcd_exact
# (CGAL), the study and the graspcd executable are not installed: CGAL stays out of the installed
# runtime.
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set(GRASPCD_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/graspcd)

# A sanitizer build's libraries need the sanitizer runtimes wherever they are linked: the installed
# targets carry the link flags (and the consumer must use the same compiler).
if(GRASPCD_SANITIZE)
  target_link_options(graspcd_core INTERFACE ${GRASPCD_SANITIZE_FLAGS})
endif()

install(TARGETS graspcd_core graspcd_bridge EXPORT graspcdTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/core ${PROJECT_SOURCE_DIR}/src/bridge
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/graspcd
        FILES_MATCHING PATTERN "*.h")
install(EXPORT graspcdTargets NAMESPACE graspcd:: DESTINATION ${GRASPCD_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/graspcdConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/graspcdConfig.cmake
                              INSTALL_DESTINATION ${GRASPCD_INSTALL_CMAKEDIR})
# 0.x: a request for 0.1 accepts 0.1.y and later 0.x (SameMajorVersion); the API may still change
# between minor versions before 1.0 (CHANGELOG.md says when).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/graspcdConfigVersion.cmake
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/graspcdConfig.cmake
              ${PROJECT_BINARY_DIR}/graspcdConfigVersion.cmake
        DESTINATION ${GRASPCD_INSTALL_CMAKEDIR})
