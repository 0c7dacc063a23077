# The architecture checks pass in a tree without .git (an unpacked source
# archive, as `make test` may run on): exports the project without .git (`git
# archive HEAD` when SOURCE_DIR is a git checkout, else a copy of the tree on disk
# without build trees), configures it (the configure step runs the dependency
# check) and runs its configure-level architecture tests (`architecture.*`: the
# portability scan and probe, the dependency check and its planted edge, the
# data-member count). Nothing of the project is compiled but the portability
# probe's few core files.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... [-DGENERATOR=Ninja] [-DLAUNCHER=ccache]
#         [-DSELF=<this test's name>] -P archive_tree_probe.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT GENERATOR)
  set(GENERATOR Ninja)
endif()
file(REMOVE_RECURSE ${WORK_DIR})
set(tree ${WORK_DIR}/tree)
file(MAKE_DIRECTORY ${tree})

find_program(GIT git)
if(EXISTS ${SOURCE_DIR}/.git AND GIT)
  set(how "git archive HEAD")
  execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} archive --format=tar
                          -o ${WORK_DIR}/tree.tar HEAD
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "git archive HEAD failed in ${SOURCE_DIR}:\n${err}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E tar xf ${WORK_DIR}/tree.tar
                  WORKING_DIRECTORY ${tree} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cannot unpack ${WORK_DIR}/tree.tar")
  endif()
else()
  set(how "a copy of the tree on disk")
  file(GLOB tops RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/* ${SOURCE_DIR}/.*)
  foreach(top IN LISTS tops)
    if(NOT top MATCHES "^(build.*|\\.git|\\.cache|\\.|\\.\\.)$")
      file(COPY ${SOURCE_DIR}/${top} DESTINATION ${tree})
    endif()
  endforeach()
endif()
if(EXISTS ${tree}/.git OR NOT EXISTS ${tree}/CMakeLists.txt)
  message(FATAL_ERROR "the exported tree (${how}) has .git or lacks CMakeLists.txt")
endif()
message(STATUS "exported the project without .git (${how}) into ${tree}")

set(configure_args -S ${tree} -B ${tree}/build -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
                   -DTWISTER_BUILD_BENCH=OFF)
if(LAUNCHER)
  list(APPEND configure_args -DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER}
       -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
# git must not find the checkout this tree may sit in (build/ of a clone): an
# archive is nowhere near one.
set(no_git ${CMAKE_COMMAND} -E env GIT_CEILING_DIRECTORIES=${WORK_DIR})
execute_process(COMMAND ${no_git} ${CMAKE_COMMAND} ${configure_args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the tree without .git failed:\n${out}\n${err}")
endif()
message(STATUS "configured (the dependency check passed at configure time)")

# Every script-level architecture test of that tree but this one (no recursion).
set(exclude "^$")
if(SELF)
  string(REPLACE "." "\\." exclude "^${SELF}$")
endif()
execute_process(COMMAND ${no_git} ${CMAKE_CTEST_COMMAND} --test-dir ${tree}/build -R "^architecture\\."
                        -E "${exclude}" --no-tests=error --output-on-failure
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "architecture tests failed in the tree without .git:\n${err}")
endif()
if(NOT out MATCHES "architecture\\.dependency_check_rejects_planted_edge[ .]+ *Passed"
   OR NOT out MATCHES "architecture\\.core_portability_check_rejects_unistd[ .]+ *Passed")
  message(FATAL_ERROR "the dependency and portability probes did not both run and pass")
endif()
