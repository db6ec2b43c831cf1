# What the three tests that compile libraps from a package's copy of the sources share
# (subproject_consumer, python_package, rust_package): each moves its package to one path,
# PACKAGE_ROOT, which they hold in turn (RESOURCE_LOCK package_root), and compiles the library
# there with the same flags. The compile commands are then the same, absolute paths included,
# so the compiler launcher's cache (ccache) gives the second and third test every object the
# first compiled: one build of the library instead of three (docs/ci-time.md). A file missing
# from a package still fails its test: its own build reads only its own copy.
#
# package_root_claim(DIR) moves DIR (a package unpacked in the test's work folder) to
# PACKAGE_ROOT, replacing what an earlier test left there. package_cmake_args holds the CMake
# arguments every package build adds (the launcher), package_build_env the `cmake -E env`
# arguments of the command that compiles: no CCACHE_BASEDIR, which would make the paths relative
# to build folders that differ.
if(NOT PACKAGE_ROOT)
  message(FATAL_ERROR "PACKAGE_ROOT is not set")
endif()

function(package_root_claim dir)
  file(REMOVE_RECURSE ${PACKAGE_ROOT})
  get_filename_component(parent ${PACKAGE_ROOT} DIRECTORY)
  file(MAKE_DIRECTORY ${parent})
  file(RENAME ${dir} ${PACKAGE_ROOT})
endfunction()

set(package_cmake_args "")
if(LAUNCHER)
  list(APPEND package_cmake_args -DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER}
       -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
set(package_build_env --unset=CCACHE_BASEDIR)
