# Copies core/, adds a file with `#include <unistd.h>` and checks that both the
# portability scan and a real configure+build of that copy fail.
file(REMOVE_RECURSE ${WORK_DIR})
file(COPY ${SOURCE_DIR}/core ${SOURCE_DIR}/cmake DESTINATION ${WORK_DIR}/src)
file(WRITE ${WORK_DIR}/src/core/src/base/probe_os.cpp "#include <unistd.h>\nint probe() { return 0; }\n")

execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK_DIR}/src/core
                        -P ${WORK_DIR}/src/cmake/CheckCorePortable.cmake
                RESULT_VARIABLE scan_rc ERROR_VARIABLE scan_err)
if(scan_rc EQUAL 0)
  message(FATAL_ERROR "the scan accepted a core/ that includes <unistd.h>")
endif()
if(NOT scan_err MATCHES "unistd.h")
  message(FATAL_ERROR "the scan failed without naming unistd.h:\n${scan_err}")
endif()
message(STATUS "scan rejected the probe as expected:\n${scan_err}")

# Now the real thing: configure and build the copied core with the probe file in
# twister_base's sources. The build must stop at the portability check.
file(APPEND ${WORK_DIR}/src/core/src/base/CMakeLists.txt "target_sources(twister_base PRIVATE probe_os.cpp)\n")
file(WRITE ${WORK_DIR}/src/CMakeLists.txt [=[
cmake_minimum_required(VERSION 3.25)
project(core_portability_probe CXX)
set(CMAKE_CXX_STANDARD 20)
list(APPEND CMAKE_MODULE_PATH ${CMAKE_CURRENT_SOURCE_DIR}/cmake)
set(PROJECT_SOURCE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
include(TwisterBuild)
find_package(glm REQUIRED)
add_subdirectory(core)
]=])
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/src -B ${WORK_DIR}/build -G Ninja
                RESULT_VARIABLE cfg_rc OUTPUT_QUIET ERROR_VARIABLE cfg_err)
if(NOT cfg_rc EQUAL 0)
  message(FATAL_ERROR "probe project did not configure:\n${cfg_err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build --target twister_base
                RESULT_VARIABLE build_rc OUTPUT_VARIABLE build_out ERROR_VARIABLE build_err)
if(build_rc EQUAL 0)
  message(FATAL_ERROR "core/ with #include <unistd.h> built; the portability check is not wired in")
endif()
if(NOT "${build_out}${build_err}" MATCHES "core/ must include only portable headers")
  message(FATAL_ERROR "the build failed, but not at the portability check:\n${build_out}${build_err}")
endif()
message(STATUS "build of core/ with <unistd.h> failed at the portability check, as it must")
