# Fails when a file under ROOT includes anything but the portable C++ standard
# library, GLM or core's own headers. An allow-list, so a new OS header cannot slip
# through by being missing from a deny-list.
#   cmake -DROOT=<dir> -P CheckCorePortable.cmake
if(NOT ROOT)
  message(FATAL_ERROR "CheckCorePortable: pass -DROOT=<core dir>")
endif()

set(allowed_std
  algorithm array atomic bit cassert cfloat climits cmath compare concepts cstddef
  cstdint cstring functional initializer_list iterator limits memory new numbers
  numeric optional ranges span string_view tuple type_traits utility variant)

file(GLOB_RECURSE files "${ROOT}/*.hpp" "${ROOT}/*.h" "${ROOT}/*.cpp" "${ROOT}/*.cc")
set(violations "")
foreach(f IN LISTS files)
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line IN LISTS lines)
    if(line MATCHES "#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"]")
      set(h "${CMAKE_MATCH_1}")
      if(h MATCHES "^glm/")
        continue()
      elseif(h MATCHES "^twister/(hal|sim|host|bridge)/")
        list(APPEND violations "${f}: ${h} (core must not know hal/, sim/ or host/)")
      elseif(h MATCHES "^twister/")
        continue()
      elseif(NOT h MATCHES "/" AND NOT h MATCHES "\\.")
        list(FIND allowed_std "${h}" idx)
        if(idx EQUAL -1)
          list(APPEND violations "${f}: <${h}> (not on core's list of portable standard headers)")
        endif()
      else()
        get_filename_component(dir "${f}" DIRECTORY)
        if(line MATCHES "\"" AND EXISTS "${dir}/${h}" AND NOT h MATCHES "\\.\\.")
          continue()  # a quoted include of a core-private file next to it
        endif()
        list(APPEND violations "${f}: <${h}> (OS or third-party header)")
      endif()
    endif()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "core/ must include only portable headers:\n  ${text}")
endif()
