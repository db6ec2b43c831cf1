# raps inside another project (tests/subproject): add_subdirectory is configured, built and
# run; FetchContent (a local SOURCE_DIR, the same add_subdirectory underneath) is configured,
# which runs the same checks of what raps leaves in the parent. A second build of the library
# would add minutes and test nothing more.
file(REMOVE_RECURSE ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/run_step.cmake)

# The compiler launcher (ccache) of the enclosing build, when it has one. No build type: raps
# must not choose one for its parent (and unoptimized, the library compiles fastest).
set(launcher "")
if(LAUNCHER)
  set(launcher -DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER} -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
foreach(how add_subdirectory FetchContent)
  set(dir ${WORK_DIR}/${how})
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/subproject -B ${dir} -DRAPS_HOW=${how}
      -DRAPS_SOURCE_DIR=${SOURCE_DIR} ${launcher})
  # The parent's test alone, none of raps's.
  run(${CMAKE_CTEST_COMMAND} --test-dir ${dir} -N)
  if(NOT last_output MATCHES "Total Tests: 1\n")
    message(FATAL_ERROR "${how}: the parent's CTest lists raps's tests too:\n${last_output}")
  endif()
endforeach()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/add_subdirectory -j ${JOBS})
run(${WORK_DIR}/add_subdirectory/consumer)
message(STATUS "add_subdirectory consumer: ${last_output}")
