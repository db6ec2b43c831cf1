# raps inside another project (tests/subproject): add_subdirectory is configured, built and
# run; FetchContent (a local SOURCE_DIR, the same add_subdirectory underneath) is configured,
# which runs the same checks of what raps leaves in the parent. A second build of the library
# would add minutes and test nothing more. raps is the library's parts alone (CMakeLists.txt,
# cmake/, include/, src/), copied where the Python and Rust packages carry them (PACKAGE_ROOT's
# native/) and built as a Release parent would, so that the compiler launcher's cache serves
# this build and the packages' alike (packaging/package_root.cmake).
file(REMOVE_RECURSE ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/run_step.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/packaging/package_root.cmake)

file(MAKE_DIRECTORY ${WORK_DIR}/raps/native)
foreach(part CMakeLists.txt cmake include src)
  file(COPY ${SOURCE_DIR}/${part} DESTINATION ${WORK_DIR}/raps/native)
endforeach()
package_root_claim(${WORK_DIR}/raps)
# FetchContent's parent sets no build type, so that the checks see raps choose none for it.
foreach(how add_subdirectory FetchContent)
  set(dir ${WORK_DIR}/${how})
  set(build_type "")
  if(how STREQUAL "add_subdirectory")
    set(build_type -DCMAKE_BUILD_TYPE=Release)
  endif()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/subproject -B ${dir} -DRAPS_HOW=${how}
      -DRAPS_SOURCE_DIR=${PACKAGE_ROOT}/native
      -DRAPS_CONSUMER=${SOURCE_DIR}/tests/consumer/consumer.c
      ${build_type} ${package_cmake_args})
  # The parent's test alone, none of raps's.
  run(${CMAKE_CTEST_COMMAND} --test-dir ${dir} -N)
  if(NOT last_output MATCHES "Total Tests: 1\n")
    message(FATAL_ERROR "${how}: the parent's CTest lists raps's tests too:\n${last_output}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -E env ${package_build_env}
    ${CMAKE_COMMAND} --build ${WORK_DIR}/add_subdirectory -j ${JOBS})
run(${WORK_DIR}/add_subdirectory/consumer)
message(STATUS "add_subdirectory consumer: ${last_output}")
