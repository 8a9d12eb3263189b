# Installation: `cmake --install BUILD [--prefix PREFIX]` installs graspcd for any MuJoCo 2.2 program
# (docs/library.md):
#   PREFIX/bin/graspcd                 the command-line tool (docs/design.md, "The command line")
#   PREFIX/include/graspcd/core/*.h    included as <graspcd/core/...>
#   PREFIX/include/graspcd/io/*.h      included as <graspcd/io/...>
#   PREFIX/include/graspcd/mujoco/*.h  included as <graspcd/mujoco/...>
#   PREFIX/lib/libgraspcd_core.a       graspcd::core    pure geometry: Eigen, qhull; no MuJoCo
#   PREFIX/lib/libgraspcd_io.a         graspcd::io      the mesh reader and text grammar
#   PREFIX/lib/libgraspcd_mujoco.a     graspcd::mujoco  the MuJoCo layer: graspcd::core + MuJoCo
#   PREFIX/lib/cmake/graspcd/          graspcdConfig.cmake, its version file and the targets
#   PREFIX/share/graspcd/mjcf/         the template scenes and their meshes, which bin/graspcd finds
#                                      beside itself (src/graspcd/version/data_dirs.h)
# so that `find_package(graspcd 0.4 REQUIRED)` gives the three targets. graspcd_exact (CGAL), the
# grasp experiment and the study are not installed as libraries: CGAL stays out of the installed
# libraries (the executable links it statically, header-only CGAL with GMP and MPFR).
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set(GRASPCD_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/graspcd)

# A sanitizer build's libraries need the sanitizer runtimes wherever they are linked: the installed
# targets carry the link flags (and the consumer must use the same compiler).
if(GRASPCD_SANITIZE)
  target_link_options(graspcd_core INTERFACE ${GRASPCD_SANITIZE_FLAGS})
endif()

install(TARGETS graspcd_core graspcd_io graspcd_mujoco EXPORT graspcdTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS graspcd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/mjcf/ DESTINATION ${GRASPCD_MJCF_INSTALL_DIR}
        PATTERN "generator" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/graspcd/core ${PROJECT_SOURCE_DIR}/src/graspcd/io
                  ${PROJECT_SOURCE_DIR}/src/graspcd/mujoco
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/graspcd
        FILES_MATCHING PATTERN "*.h")
# Headers that moved keep their installed path, forwarding to the new one (src/compat/).
install(FILES ${PROJECT_SOURCE_DIR}/src/compat/core/warnings.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/graspcd/core)
install(EXPORT graspcdTargets NAMESPACE graspcd:: DESTINATION ${GRASPCD_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/graspcdConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/graspcdConfig.cmake
                              INSTALL_DESTINATION ${GRASPCD_INSTALL_CMAKEDIR})
# 0.x: a request for 0.3 accepts 0.3.y and later 0.x (SameMajorVersion); the API may still change
# between minor versions before 1.0 (CHANGELOG.md says when).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/graspcdConfigVersion.cmake
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/graspcdConfig.cmake
              ${PROJECT_BINARY_DIR}/graspcdConfigVersion.cmake
        DESTINATION ${GRASPCD_INSTALL_CMAKEDIR})
