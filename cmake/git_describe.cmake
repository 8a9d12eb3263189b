# Run at every build (src/CMakeLists.txt, target graspcd_describe): writes OUT, a C++ source that
# defines the commit this build was made from and whether the work tree was clean
# (`git describe --always --dirty`; "unknown" outside git). configure_file rewrites OUT only when
# its text changes, so an unchanged tree recompiles nothing.
#   cmake -DSOURCE_DIR=... -DIN=provenance.cpp.in -DOUT=... -P git_describe.cmake
set(GRASPCD_COMMIT "unknown")
set(GRASPCD_DIRTY "false")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} describe --always --dirty --abbrev=12
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(rc EQUAL 0 AND out)
    set(GRASPCD_COMMIT "${out}")
    if(out MATCHES "-dirty$")
      set(GRASPCD_DIRTY "true")
    endif()
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)
