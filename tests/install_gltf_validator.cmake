# Installs the Khronos glTF validator (npm package gltf-validator, pinned) into PREFIX unless it
# is already there. Run as the CTest fixture of the glTF tests: a machine without npm or without
# the npm registry fails those tests rather than skipping them.
#   cmake -DNPM=... -DPREFIX=... -DVERSION=... -P install_gltf_validator.cmake
if(EXISTS "${PREFIX}/node_modules/gltf-validator/package.json")
  file(READ "${PREFIX}/node_modules/gltf-validator/package.json" _package)
  if(_package MATCHES "\"version\": *\"${VERSION}\"")
    message(STATUS "gltf-validator ${VERSION} already in ${PREFIX}")
    return()
  endif()
endif()
if(NOT NPM OR NPM MATCHES "NOTFOUND")
  message(FATAL_ERROR "npm not found: install Debian's nodejs and npm (./quickstart does)")
endif()
file(MAKE_DIRECTORY "${PREFIX}")
execute_process(COMMAND "${NPM}" install --no-audit --no-fund --prefix "${PREFIX}"
                        "gltf-validator@${VERSION}"
                RESULT_VARIABLE _result)
if(NOT _result EQUAL 0)
  message(FATAL_ERROR "npm install gltf-validator@${VERSION} failed (${_result})")
endif()
