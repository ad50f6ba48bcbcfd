# check_info.cmake: runs `rsl2cl --info INPUT` and compares stdout with EXPECTED.
execute_process(COMMAND ${RSL2CL} --info ${INPUT} OUTPUT_VARIABLE out
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rsl2cl failed (${rc}): ${err}")
endif()
file(READ ${EXPECTED} want)
if(NOT out STREQUAL want)
  message(FATAL_ERROR "--info output differs.\n--- got:\n${out}\n--- expected:\n${want}")
endif()
