# fuzz_target.cmake: rd_fuzz_target(), a libFuzzer target built by clang++ (the project
# itself may build with g++; scripts/setup.sh installs clang) with ASan and UBSan, both
# fatal, and a CTest case that fuzzes it for 20 s from seed files.
#   rd_fuzz_target(<name> TEST <test name> SOURCES <.cpp...> [FLAGS <compile flags...>]
#                  [LIBS <link flags...>] [DEPENDS <headers...>] SEEDS <files...>)
find_program(RD_CLANGXX NAMES clang++ clang++-14)
function(rd_fuzz_target name)
  cmake_parse_arguments(F "" "TEST" "SOURCES;FLAGS;LIBS;DEPENDS;SEEDS" ${ARGN})
  set(bin ${CMAKE_BINARY_DIR}/bin/${name})
  add_custom_command(
    OUTPUT ${bin}
    COMMAND ${RD_CLANGXX} -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined
            -fno-sanitize-recover=all ${F_FLAGS} ${F_SOURCES} ${F_LIBS} -o ${bin}
    DEPENDS ${F_SOURCES} ${F_DEPENDS}
    COMMENT "Building the fuzz target ${name} with clang++ (libFuzzer, ASan, UBSan)"
    VERBATIM)
  add_custom_target(${name}_clang ALL DEPENDS ${bin})
  file(COPY ${F_SEEDS} DESTINATION ${CMAKE_CURRENT_BINARY_DIR}/fuzz_seeds)
  add_test(NAME ${F_TEST}
           COMMAND ${bin} -max_total_time=20 -seed=1 -rss_limit_mb=2048 -timeout=10
                   -artifact_prefix=${CMAKE_CURRENT_BINARY_DIR}/
                   ${CMAKE_CURRENT_BINARY_DIR}/fuzz_seeds)
  set_tests_properties(${F_TEST} PROPERTIES TIMEOUT 120 LABELS fuzz)
endfunction()
