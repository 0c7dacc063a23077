# Counts the data members of every top-level class and struct in the headers and
# sources under DIRS (a ;-list) and fails naming each one with more than MAX.
# A data member: a line indented two spaces inside the type's braces that declares
# one name, with or without an initialiser, and no parameter list (methods, using,
# static and friend lines are not members). Types nested inside are not counted into
# their parent. Usage: cmake -DDIRS=a,b -DMAX=15 -P member_count_check.cmake
string(REPLACE "," ";" DIRS "${DIRS}")
if(NOT DEFINED MAX)
  set(MAX 15)
endif()
set(failures "")
set(checked 0)
foreach(dir IN LISTS DIRS)
  file(GLOB_RECURSE files "${dir}/*.hpp" "${dir}/*.cpp")
  foreach(f IN LISTS files)
    file(STRINGS "${f}" lines)
    set(current "")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "//.*$" "" line "${line}")
      if(line MATCHES "^(class|struct) ([A-Za-z0-9_]+)[^;]*\\{ *$")
        set(current "${CMAKE_MATCH_2}")
        set(count 0)
        math(EXPR checked "${checked} + 1")
      elseif(current AND line MATCHES "^};")
        if(count GREATER MAX)
          list(APPEND failures "${f}: ${current} has ${count} data members (at most ${MAX})")
        endif()
        set(current "")
      elseif(current AND line MATCHES "^  [A-Za-z]" AND
             NOT line MATCHES "^  (static|using|friend|return|enum|typedef|public|private|protected|virtual|explicit|template|struct|class)[ :]" AND
             line MATCHES "^  [A-Za-z_:<>, &*0-9]+[ &*][A-Za-z_][A-Za-z0-9_]*( = [^;]*| ?\\{[^;]*\\})?; *$")
        math(EXPR count "${count} + 1")
      endif()
    endforeach()
  endforeach()
endforeach()
if(failures)
  list(JOIN failures "\n" text)
  message(FATAL_ERROR "classes with too many data members:\n${text}")
endif()
message(STATUS "member count: ${checked} types checked, none over ${MAX}")
