# Writes a tool's manual page from its --help text (what help2man does, without needing it):
#   cmake -DTOOL=path/raps-param -DNAME=raps-param -DSUMMARY="..." -DVERSION=0.1.0
#         -DOUTPUT=raps-param.1 -P man_page.cmake
# The help text is the reference and stays the only copy; the page shows it verbatim.
execute_process(COMMAND ${TOOL} --help RESULT_VARIABLE rc OUTPUT_VARIABLE help ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR help STREQUAL "")
  message(FATAL_ERROR "${TOOL} --help failed (${rc}): ${err}")
endif()
# roff: a backslash is an escape, and a line starting with . or ' is a request.
string(REPLACE "\\" "\\e" help "${help}")
string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" help "${help}")
string(TOUPPER "${NAME}" upper)
file(WRITE ${OUTPUT} ".TH ${upper} 1 \"\" \"raps ${VERSION}\" \"User Commands\"
.SH NAME
${NAME} \\- ${SUMMARY}
.SH DESCRIPTION
.nf
${help}.fi
.SH SEE ALSO
The raps README (r-adaptive surface parameterization) and include/raps.h, the C API.
")
