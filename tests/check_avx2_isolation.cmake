# The AVX2 build of the dense kernel must define nothing a baseline code path could link to:
# only its own function and its private Eigen (namespace raps_eigen_avx2). A shared template
# instance compiled for AVX2 would crash processors without it.
execute_process(COMMAND nm --defined-only ${OBJECT} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${OBJECT}")
endif()
string(REPLACE "\n" ";" lines "${symbols}")
foreach(line IN LISTS lines)
  if(line MATCHES "^[0-9a-fA-F]+ [TWVBDR] (.+)$")
    set(name "${CMAKE_MATCH_1}")
    # Mangled names: anything involving the private Eigen is its own instance.
    if(NOT name MATCHES "raps_eigen_avx2|partial_lu_avx2|partial_cholesky_avx2|^DW\\.ref\\.__gxx_personality_v0$")
      message(SEND_ERROR "AVX2 object defines a shareable symbol: ${name}")
    endif()
  endif()
endforeach()
