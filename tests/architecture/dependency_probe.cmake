# Copies the project's CMake files (and empty stand-ins of its sources), plants one
# wrong edge (core's math library linking hal/posix: core pointing up at the OS
# side) and checks that configuring that copy fails at the dependency check, naming
# the edge. The tree is read from the disk, not from git: the test passes in an
# unpacked source archive (no .git). Build trees (build*/) and dot folders are
# skipped.
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${WORK_DIR})
file(GLOB tops RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/*)
set(files "")
foreach(top IN LISTS tops)
  if(top MATCHES "^(build|\\.)")
    continue()
  endif()
  if(IS_DIRECTORY ${SOURCE_DIR}/${top})
    file(GLOB_RECURSE found RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/${top}/*)
    list(APPEND files ${found})
  else()
    list(APPEND files ${top})
  endif()
endforeach()
if(NOT "CMakeLists.txt" IN_LIST files OR NOT "docs/architecture.md" IN_LIST files)
  message(FATAL_ERROR "${SOURCE_DIR} does not look like the project's source tree")
endif()
foreach(f IN LISTS files)
  if(f MATCHES "CMakeLists.txt$|\\.cmake$|\\.md$|CMakePresets.json$")
    get_filename_component(dir "${f}" DIRECTORY)
    file(COPY ${SOURCE_DIR}/${f} DESTINATION ${WORK_DIR}/src/${dir})
  endif()
endforeach()
# Configuring needs the CMake files only; sources are not compiled here, so empty
# stand-ins of every other source file are enough.
foreach(f IN LISTS files)
  if(NOT EXISTS ${WORK_DIR}/src/${f} AND f MATCHES "\\.(cpp|hpp|h)$")
    file(WRITE ${WORK_DIR}/src/${f} "")
  endif()
endforeach()

file(APPEND ${WORK_DIR}/src/hal/posix/CMakeLists.txt
     "target_link_libraries(twister_math PRIVATE twister_hal_posix)  # planted\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/src -B ${WORK_DIR}/build -G Ninja
                        -DCMAKE_BUILD_TYPE=Release -DTWISTER_BUILD_BENCH=OFF
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "configure accepted core/src/math -> hal/posix; the check is not wired in")
endif()
if(NOT err MATCHES "twister_math \\(core/src/math\\) -> twister_hal_posix \\(hal/posix\\): not allowed")
  message(FATAL_ERROR "configure failed, but not at the dependency check:\n${err}")
endif()
message(STATUS "the planted edge was refused as it must be:\n${err}")
