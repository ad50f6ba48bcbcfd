# check_layout.cmake: the top level is fixed by the design card; fail if a part is missing.
foreach(entry CMakeLists.txt README.md cl host rsl2cl rib tests benchmarks examples .ci/run)
  if(NOT EXISTS "${ROOT}/${entry}")
    message(FATAL_ERROR "top-level entry missing: ${entry}")
  endif()
endforeach()
