# The Debian packages (cmake/debian_packages.cmake): `cpack -G DEB` in this build tree, each
# package checked for what it must hold, then installed with `dpkg --root` into a scratch root
# whose dpkg database holds this machine's entries for the packages' other dependencies (the C
# and C++ runtimes, stb), so that dpkg checks every dependency as `dpkg -i` would, without
# root's system or a chroot. Against that root a C program compiles with `pkg-config raps` and
# runs, a CMake project finds raps, and the tools run and have their manual pages.
cmake_minimum_required(VERSION 3.16)  # IN_LIST, continue()
file(REMOVE_RECURSE ${WORK_DIR})
set(root ${WORK_DIR}/root)
file(MAKE_DIRECTORY ${root})

include(${CMAKE_CURRENT_LIST_DIR}/../run_step.cmake)

run(${CPACK} -G DEB -B ${WORK_DIR}/debs --config ${BUILD_DIR}/CPackConfig.cmake)

# Each package by name, with what it must hold (a path under /usr, a regular expression).
set(expect_libraps0 "lib/libraps\\.so\\.0")
set(expect_libraps-dev "include/raps\\.h" "lib/libraps\\.so[ \n]" "lib/cmake/raps/rapsConfig\\.cmake"
    "lib/pkgconfig/raps\\.pc")
set(expect_raps-tools "bin/raps-param" "bin/raps-gltf" "share/man/man1/raps-param\\.1\\.gz"
    "share/man/man1/raps-gltf\\.1\\.gz" "share/raps/per-asset\\.mk")
foreach(package libraps0 libraps-dev raps-tools)
  file(GLOB deb ${WORK_DIR}/debs/${package}_*.deb)
  if(NOT deb)
    message(FATAL_ERROR "cpack made no ${package} package")
  endif()
  run(${DPKG_DEB} --contents ${deb})
  set(contents "${last_output}")
  foreach(pattern IN LISTS expect_${package})
    if(NOT contents MATCHES "\\./usr/${pattern}")
      message(FATAL_ERROR "${package} lacks ${pattern}:\n${contents}")
    endif()
  endforeach()
  run(${DPKG_DEB} --field ${deb} Depends)
  message(STATUS "${package}: Depends: ${last_output}")
  if(NOT package STREQUAL "libraps0" AND NOT last_output MATCHES "libraps0 \\(= ")
    message(FATAL_ERROR "${package} does not depend on its libraps0: ${last_output}")
  endif()
  list(APPEND debs ${deb})
  string(APPEND depends ", ${last_output}")
endforeach()

# A dpkg database with the dependencies from outside raps, as this machine has them installed.
set(admin ${root}/var/lib/dpkg)
file(MAKE_DIRECTORY ${admin}/info ${admin}/updates ${admin}/triggers)
file(WRITE ${admin}/available "")
string(REGEX MATCHALL "[,|] *[a-z0-9][a-z0-9.+-]+" names "${depends}")
set(status "")
set(seen "")
foreach(name IN LISTS names)
  string(REGEX REPLACE "^[,|] *" "" name "${name}")
  if(name MATCHES "^(libraps0|libraps-dev|raps-tools)$" OR name IN_LIST seen)
    continue()
  endif()
  list(APPEND seen ${name})
  execute_process(COMMAND ${DPKG_QUERY} --status ${name} OUTPUT_VARIABLE entry RESULT_VARIABLE rc)
  if(rc EQUAL 0)
    string(APPEND status "${entry}\n")
  endif()
endforeach()
file(WRITE ${admin}/status "${status}")
run(${DPKG} --root=${root} --force-script-chrootless -i ${debs})
run(${DPKG_QUERY} --root=${root} --show --showformat=\${db:Status-Abbrev}\${Package}\n
    libraps0 libraps-dev raps-tools)
if(NOT last_output MATCHES "ii +libraps0\n" OR NOT last_output MATCHES "ii +libraps-dev\n"
   OR NOT last_output MATCHES "ii +raps-tools\n")
  message(FATAL_ERROR "dpkg did not install the three packages:\n${last_output}")
endif()

file(GLOB pc_file ${root}/usr/lib*/pkgconfig/raps.pc ${root}/usr/lib/*/pkgconfig/raps.pc)
get_filename_component(pc_dir "${pc_file}" DIRECTORY)
get_filename_component(libdir "${pc_dir}" DIRECTORY)

# A C program through pkg-config alone.
execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir}
                ${PKG_CONFIG} --cflags --libs raps
                OUTPUT_VARIABLE flags RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs raps failed against ${pc_dir}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CC} -std=c99 ${SOURCE_DIR}/tests/consumer/consumer.c -o ${WORK_DIR}/pkg-consumer ${flags})
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${WORK_DIR}/pkg-consumer)
message(STATUS "pkg-config consumer: ${last_output}")

# A CMake project through find_package(raps).
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/cmake-consumer
    -DCMAKE_PREFIX_PATH=${root}/usr)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/cmake-consumer)
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${WORK_DIR}/cmake-consumer/consumer)

# The tools: a disk mapped by raps-param, raps-gltf's usage, both manual pages readable.
file(WRITE ${WORK_DIR}/square.obj "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n")
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${root}/usr/bin/raps-param
    ${WORK_DIR}/square.obj -o ${WORK_DIR}/square_uv.obj)
file(STRINGS ${WORK_DIR}/square_uv.obj uv_lines REGEX "^vt ")
list(LENGTH uv_lines uv_count)
if(NOT uv_count EQUAL 4)
  message(FATAL_ERROR "raps-param from the package wrote ${uv_count} vt lines, not 4")
endif()
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${root}/usr/bin/raps-gltf --help)
foreach(tool raps-param raps-gltf)
  run(gzip -dc ${root}/usr/share/man/man1/${tool}.1.gz)
  if(NOT last_output MATCHES "^\\.TH [A-Z-]+ 1" OR NOT last_output MATCHES "usage: ${tool}")
    message(FATAL_ERROR "${tool}.1.gz is not its manual page:\n${last_output}")
  endif()
endforeach()
