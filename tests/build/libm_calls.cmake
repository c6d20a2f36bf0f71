# Fails when a library on the state's path (LIBS, separated by '|') calls a
# libm function that IEEE 754 does not require to be correctly rounded: its
# last bit may differ between C libraries, CPUs and glibc's start-up choice
# of variant, and a pinned state hash with it. The pose library's mr_sin,
# mr_cos and mr_acos stand in for them; sqrt, fabs, floor, fmin and fmax
# are exact and allowed. Arguments (-D): NM, LIBS.
set(inexact "sin|cos|tan|sincos|asin|acos|atan|atan2|sinh|cosh|tanh|asinh|acosh|atanh")
string(APPEND inexact "|exp|exp2|exp10|expm1|log|log2|log10|log1p|pow|cbrt|hypot")
string(APPEND inexact "|erf|erfc|lgamma|tgamma|j0|j1|jn|y0|y1|yn")
string(REPLACE "|" ";" libs "${LIBS}")
set(bad "")
foreach(lib IN LISTS libs)
  execute_process(COMMAND ${NM} -u ${lib} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${lib}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^ *U (_*(${inexact})[fl]?)(@.*)?$")
      get_filename_component(name ${lib} NAME)
      list(APPEND bad "${name}: ${CMAKE_MATCH_1}")
    endif()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "libm functions that may round differently by machine: ${bad}")
endif()
message(STATUS "no inexact libm call in ${LIBS}")
