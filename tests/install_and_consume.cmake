# Installs the build tree into a fresh prefix, then builds and runs a small C program against
# the installed copy twice: through find_package(raps) and through pkg-config.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

include(${CMAKE_CURRENT_LIST_DIR}/run_step.cmake)

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f include/raps.h)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "${f} was not installed")
  endif()
endforeach()
file(GLOB_RECURSE config_files ${prefix}/*/rapsConfig.cmake)
file(GLOB_RECURSE pc_files ${prefix}/*/raps.pc)
if(NOT config_files OR NOT pc_files)
  message(FATAL_ERROR "rapsConfig.cmake or raps.pc missing under ${prefix}")
endif()
list(GET pc_files 0 pc_file)
get_filename_component(pc_dir ${pc_file} DIRECTORY)
get_filename_component(libdir ${pc_dir} DIRECTORY)

# 1. CMake: find_package(raps) with the prefix on CMAKE_PREFIX_PATH.
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/cmake-consumer -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/cmake-consumer)
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${WORK_DIR}/cmake-consumer/consumer)
message(STATUS "find_package consumer: ${last_output}")

# 2. pkg-config: compile and link with the flags it prints, nothing else.
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CC NAMES cc gcc clang REQUIRED)
set(static_flag "")
if(STATIC)
  set(static_flag --static)  # a static libraps needs its private libraries (the C++ runtime)
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir}
                ${PKG_CONFIG} --cflags --libs ${static_flag} raps
                OUTPUT_VARIABLE flags RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs raps failed")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CC} -std=c99 ${CONSUMER_DIR}/consumer.c -o ${WORK_DIR}/pkg-consumer ${flags})
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${WORK_DIR}/pkg-consumer)
message(STATUS "pkg-config consumer: ${last_output}")
