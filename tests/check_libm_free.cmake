# libraps calls no C library function whose last bit may differ between C libraries,
# architectures or processors (docs/reproducibility.md): the elementary functions are the
# project's own (src/core/portable_math.h), and so are complex modulus and division (the compiler
# runtime's __divdc3 is built with fused multiply-adds on some architectures). Exact functions
# (sqrt, floor, fmod, remainder) may be called. And no fused multiply-add instruction anywhere
# in the library (x86-64's vfmadd..., aarch64's fmadd/fmla...), which would round a*b+c once
# where another build rounds twice.
#   cmake -DLIBRARY=libraps.so|libraps.a [-DNM=nm] [-DOBJDUMP=objdump] -P check_libm_free.cmake
if(NOT NM)
  set(NM nm)
endif()
if(NOT OBJDUMP)
  set(OBJDUMP objdump)
endif()
execute_process(COMMAND ${NM} --undefined-only ${LIBRARY} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} failed on ${LIBRARY}")
endif()
set(inexact "exp|exp2|exp10|expm1|log|log2|log10|log1p|logb|pow|pow10|sin|cos|tan|sincos|asin")
string(APPEND inexact "|acos|atan|atan2|sinh|cosh|tanh|asinh|acosh|atanh|cbrt|hypot|erf|erfc")
string(APPEND inexact "|lgamma|tgamma|cabs|carg|cexp|clog|cpow|csqrt|csin|ccos|ctan")
string(REPLACE "\n" ";" lines "${symbols}")
set(found "")
foreach(line IN LISTS lines)
  if(line MATCHES " U ([^@ ]+)")
    set(name "${CMAKE_MATCH_1}")
    if(name MATCHES "^(__)?(${inexact})[fl]?(_finite)?$" OR name MATCHES "^__div[sdxt]c3$")
      list(APPEND found ${name})
    endif()
  endif()
endforeach()
if(found)
  list(REMOVE_DUPLICATES found)
  message(SEND_ERROR "${LIBRARY} calls ${found}: use src/core/portable_math.h or portable_complex.h")
endif()
execute_process(COMMAND ${OBJDUMP} -d ${LIBRARY}
                COMMAND grep -m 1 -E "\t(vfn?m(add|sub)[0-9a-z]*|fn?m(add|sub)|fml[as])[ \t]"
                OUTPUT_VARIABLE fused RESULT_VARIABLE rc)
if(fused)
  message(SEND_ERROR "${LIBRARY} uses fused multiply-add: ${fused}")
elseif(NOT rc EQUAL 1)
  message(FATAL_ERROR "${OBJDUMP} -d ${LIBRARY} | grep failed (${rc})")
endif()
