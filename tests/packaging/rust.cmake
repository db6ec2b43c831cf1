# The Rust crates as published: `cargo package` makes raps-sys and raps into .crate files,
# which are unpacked outside the repository; a consumer crate depending on them builds offline
# with the default `bundled` feature (libraps compiled by raps-sys's build.rs from the sources
# its package carries, linked statically) and runs its test with no libraps.so anywhere on the
# loader's path. A source file missing from the package fails the build here.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/crates)

include(${CMAKE_CURRENT_LIST_DIR}/../run_step.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/package_root.cmake)

# One crate at a time: raps names raps-sys by version, which no registry offline has, so a
# patch points it at the sources. Debian bookworm's cargo (1.65) cannot package a workspace's
# unpublished dependencies together (`--workspace` resolves them from crates.io there).
run(${CMAKE_COMMAND} -E env CARGO_TARGET_DIR=${WORK_DIR}/package-target
    ${CARGO} package --offline --no-verify --allow-dirty --package raps-sys
    --manifest-path ${SOURCE_DIR}/bindings/rust/Cargo.toml)
run(${CMAKE_COMMAND} -E env CARGO_TARGET_DIR=${WORK_DIR}/package-target
    ${CARGO} package --offline --no-verify --allow-dirty --package raps
    --config "patch.crates-io.raps-sys.path=\"${SOURCE_DIR}/bindings/rust/raps-sys\""
    --manifest-path ${SOURCE_DIR}/bindings/rust/Cargo.toml)
foreach(crate raps-sys raps)
  file(GLOB packaged ${WORK_DIR}/package-target/package/${crate}-[0-9]*.crate)
  if(NOT packaged)
    message(FATAL_ERROR "cargo package made no ${crate} crate")
  endif()
  run(${CMAKE_COMMAND} -E chdir ${WORK_DIR}/crates ${CMAKE_COMMAND} -E tar xzf ${packaged})
  file(GLOB unpacked LIST_DIRECTORIES true ${WORK_DIR}/crates/${crate}-[0-9]*)
  string(MAKE_C_IDENTIFIER "${crate}" var)
  set(${var}_dir ${unpacked})
endforeach()

# raps-sys carries the library's sources: built at PACKAGE_ROOT (package_root.cmake).
package_root_claim(${raps_sys_dir})
set(RAPS_CRATE ${raps_dir})
set(RAPS_SYS_CRATE ${PACKAGE_ROOT})
configure_file(${SOURCE_DIR}/tests/packaging/rust-consumer/Cargo.toml.in
               ${WORK_DIR}/consumer/Cargo.toml @ONLY)
file(COPY ${SOURCE_DIR}/tests/packaging/rust-consumer/src DESTINATION ${WORK_DIR}/consumer)

# The enclosing build's compiler launcher (ccache) reaches the bundled CMake build; no
# RAPS_LIB_DIR or LD_LIBRARY_PATH: nothing but the bundled static library can satisfy the link.
list(JOIN package_cmake_args " " cmake_args)
run(${CMAKE_COMMAND} -E env --unset=RAPS_LIB_DIR --unset=LD_LIBRARY_PATH ${package_build_env}
    CARGO_TARGET_DIR=${WORK_DIR}/consumer/target NUM_JOBS=${JOBS} "RAPS_CMAKE_ARGS=${cmake_args}"
    ${CARGO} test --offline --jobs ${JOBS} --manifest-path ${WORK_DIR}/consumer/Cargo.toml)
# cargo prints the test results on stdout and its progress on stderr.
set(last_output "${last_output}${last_error}")
message(STATUS "consumer crate: ${last_output}")
if(NOT last_output MATCHES "test result: ok. 1 passed")
  message(FATAL_ERROR "the consumer crate's test did not run")
endif()
# Linked statically: the test program names no libraps.so to load.
file(GLOB programs ${WORK_DIR}/consumer/target/debug/deps/raps_consumer-*)
foreach(program IN LISTS programs)
  if(NOT program MATCHES "\\.d$")
    file(STRINGS ${program} needed REGEX "^libraps\\.so")
    if(needed)
      message(FATAL_ERROR "${program} loads ${needed}: the bundled build was not linked statically")
    endif()
  endif()
endforeach()
