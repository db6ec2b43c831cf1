# The AVX2 build of the dense kernels must define nothing a baseline code path could link to:
# only its own two kernels. A shared template or inline instance compiled for AVX2 (a Debug
# build emits std::fill or std::abs out of line, as weak symbols) could be the copy the linker
# keeps for every caller, which would then crash processors without AVX2. Run in every build
# type's tree (./quickstart configures a Debug one for it).
execute_process(COMMAND nm --defined-only ${OBJECT} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${OBJECT}")
endif()
string(REPLACE "\n" ";" lines "${symbols}")
foreach(line IN LISTS lines)
  if(line MATCHES "^[0-9a-fA-F]+ [TWVBDRGSuiu] (.+)$")
    set(name "${CMAKE_MATCH_1}")
    if(NOT name MATCHES "^_ZN4raps15partial_lu_avx2EPdiiPKdPKNS_14KernelProgressE$|^_ZN4raps21partial_cholesky_avx2EPdiiPKdPKNS_14KernelProgressE$")
      message(SEND_ERROR "AVX2 object defines a shareable symbol: ${name}")
    endif()
  endif()
endforeach()
# And no fused multiply-add: it rounds a*b+c once where the baseline kernels round twice, so the
# two variants would not give the same bits (docs/reproducibility.md).
execute_process(COMMAND objdump -d ${OBJECT} OUTPUT_VARIABLE code RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "objdump failed on ${OBJECT}")
endif()
if(code MATCHES "(vfn?m(add|sub)[0-9a-z]*)")
  message(SEND_ERROR "AVX2 object uses fused multiply-add (${CMAKE_MATCH_1})")
endif()
