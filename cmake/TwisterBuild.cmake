# Build helpers shared by every layer: warnings, core flags, tests, fuzzers.
include_guard(GLOBAL)

# Warnings for the project's own code (third-party headers come in as SYSTEM).
set(TWISTER_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion)
# Tests and benchmarks: the same minus the conversion pair, which fights gtest/benchmark macros.
set(TWISTER_TEST_WARNINGS -Wall -Wextra -Wpedantic -Wshadow)

function(twister_warnings target)
  set(w ${TWISTER_WARNINGS})
  if(ARGV1 STREQUAL "TEST")
    set(w ${TWISTER_TEST_WARNINGS})
  endif()
  if(TWISTER_WERROR)
    list(APPEND w -Werror)
  endif()
  target_compile_options(${target} PRIVATE ${w})
endfunction()

# core/ must stay portable: this check runs before any core library compiles.
if(NOT TARGET twister_core_portability)
  add_custom_target(twister_core_portability ALL
    COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR}/core
            -P ${PROJECT_SOURCE_DIR}/cmake/CheckCorePortable.cmake
    COMMENT "Checking that core/ includes no OS, device-library or host header"
    VERBATIM)
endif()

# twister_core_library(<part> SOURCES ... [DEPS ...])
# A static library twister_<part>: C++20, no exceptions, no RTTI, GLM + std only.
function(twister_core_library part)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(target twister_${part})
  if(ARG_SOURCES)
    add_library(${target} STATIC ${ARG_SOURCES})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/core/include)
    target_compile_options(${target} PRIVATE -fno-exceptions -fno-rtti)
    target_link_libraries(${target} PUBLIC glm::glm ${ARG_DEPS})
    twister_warnings(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR}/core/include)
    target_link_libraries(${target} INTERFACE glm::glm ${ARG_DEPS})
  endif()
  add_dependencies(${target} twister_core_portability)
endfunction()

# The area label of a test is the folder it lives in under tests/, which mirrors
# the code it tests: tests/core/math -> "core/math", tests/hal/twister-station ->
# "hal/twister-station" (`ctest -L ^hal/` runs every hal test). It is a directory
# property, so CTest gives it to every test of the folder, also to those
# gtest_discover_tests finds at test time. Capability labels (fuzz, architecture,
# integrity, ...) come on top through LABELS.
function(twister_test_area)
  file(RELATIVE_PATH area ${PROJECT_SOURCE_DIR}/tests ${CMAKE_CURRENT_SOURCE_DIR})
  set_property(DIRECTORY PROPERTY LABELS ${area})
endfunction()

# twister_add_test(<name> SOURCES ... [LIBS ...] [LABELS ...] [ENVIRONMENT ...] [TIMEOUT s])
# One GoogleTest executable; each test case becomes a CTest test carrying the area
# label plus LABELS (and ENVIRONMENT, e.g. an LD_PRELOAD of a device emulator).
function(twister_add_test name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;LIBS;LABELS;ENVIRONMENT" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} twister_test_support GTest::gmock GTest::gtest_main)
  twister_warnings(${name} TEST)
  twister_test_area()
  # gtest_discover_tests flattens PROPERTIES: one capability label at most here.
  set(properties "")
  if(ARG_LABELS)
    list(LENGTH ARG_LABELS n)
    if(n GREATER 1)
      message(FATAL_ERROR "twister_add_test(${name}): one capability label at most")
    endif()
    list(APPEND properties LABELS ${ARG_LABELS})
  endif()
  if(ARG_ENVIRONMENT)
    list(APPEND properties ENVIRONMENT "${ARG_ENVIRONMENT}")
  endif()
  if(ARG_TIMEOUT)
    list(APPEND properties TIMEOUT ${ARG_TIMEOUT})
  endif()
  gtest_discover_tests(${name}
    DISCOVERY_MODE PRE_TEST
    TEST_PREFIX "${name}."
    PROPERTIES ${properties})
endfunction()

# twister_add_script_test(<name> COMMAND ... [LABELS ...] [PROPERTIES ...])
# A CTest test that runs a command (a script or a program), labelled like
# twister_add_test: its area plus LABELS; PROPERTIES go to set_tests_properties.
function(twister_add_script_test name)
  cmake_parse_arguments(ARG "" "" "COMMAND;LABELS;PROPERTIES" ${ARGN})
  add_test(NAME ${name} COMMAND ${ARG_COMMAND})
  twister_test_area()
  if(ARG_LABELS)
    set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}")
  endif()
  if(ARG_PROPERTIES)
    set_tests_properties(${name} PROPERTIES ${ARG_PROPERTIES})
  endif()
endfunction()

# twister_add_fuzzer(<name> SOURCES ... [LIBS ...] [LABELS ...])
# The harness defines LLVMFuzzerTestOneInput; its seed corpus is
# tests/fuzz/corpus/<name>/. In the fuzz preset (clang) it is a libFuzzer binary with
# ASan+UBSan and a bounded CTest smoke run; in other builds it is linked with a replay
# driver that runs the corpus plus deterministic mutations (CTest label "fuzz", plus
# LABELS).
set(TWISTER_FUZZ_SECONDS 10 CACHE STRING "Length of the libFuzzer smoke run per target")
function(twister_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS;ARGS" ${ARGN})
  set(corpus ${PROJECT_SOURCE_DIR}/tests/fuzz/corpus/${name})
  set(labels fuzz ${ARG_LABELS})
  add_executable(${name} ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  twister_warnings(${name} TEST)
  if(TWISTER_FUZZ)
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer)
    target_link_options(${name} PRIVATE -fsanitize=fuzzer)
    set(work ${CMAKE_BINARY_DIR}/corpus/${name})
    file(MAKE_DIRECTORY ${work})
    add_test(NAME fuzz.${name}
      COMMAND ${name} -max_total_time=${TWISTER_FUZZ_SECONDS} -rss_limit_mb=2048
              -print_final_stats=1 ${ARG_ARGS} ${work} ${corpus})
    set_tests_properties(fuzz.${name} PROPERTIES LABELS "${labels}")
  else()
    target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support/fuzz_replay_main.cpp)
    add_test(NAME fuzz_replay.${name} COMMAND ${name} ${corpus} 20000)
    set_tests_properties(fuzz_replay.${name} PROPERTIES LABELS "${labels}")
  endif()
endfunction()
