# The studio's rooms (docs/architecture.md): studio/design/ (the editing
# model) and studio/live/ (the LCM node) hold no window code. Their
# libraries link no GUI library, so an ImGui header does not compile there;
# GLFW's and OpenGL's headers sit in /usr/include and would, so this check
# refuses them by name, and refuses the window's own folders (studio/ui/,
# studio/app/) too.
#
# Two uses, one rule:
#   include(cmake/check_studio_rooms.cmake); mrsim_check_studio_rooms(<dir>...)
#     at configure time: a file breaking the rule stops the configure.
#   cmake -DMRSIM_ROOMS_DIRS="<dir>;<dir>" -P cmake/check_studio_rooms.cmake
#     as a test (tests/studio/CMakeLists.txt): fails naming file and line.
set(MRSIM_ROOMS_FORBIDDEN
    "^[ \t]*#[ \t]*include[ \t]*[<\"]((imgui[a-z_]*|backends/imgui[a-z_0-9]*)\\.h|GLFW/|GL/|GLES[0-9]*/|EGL/|studio/ui/|studio/app/)")

function(mrsim_check_studio_rooms)
  set(bad "")
  foreach(dir ${ARGN})
    file(GLOB_RECURSE files ${dir}/*.h ${dir}/*.hpp ${dir}/*.cc ${dir}/*.cpp)
    list(SORT files)
    foreach(f ${files})
      file(STRINGS ${f} lines)
      set(n 0)
      foreach(line IN LISTS lines)
        math(EXPR n "${n} + 1")
        if(line MATCHES "${MRSIM_ROOMS_FORBIDDEN}")
          string(STRIP "${line}" line)
          string(APPEND bad "\n  ${f}:${n}: ${line}")
        endif()
      endforeach()
    endforeach()
  endforeach()
  if(NOT bad STREQUAL "")
    message(FATAL_ERROR
      "studio rooms: studio/design and studio/live hold no window code "
      "(no ImGui, GLFW, OpenGL/EGL, studio/ui or studio/app include); "
      "move the file to studio/ui/ or drop the include:${bad}")
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND DEFINED MRSIM_ROOMS_DIRS)
  mrsim_check_studio_rooms(${MRSIM_ROOMS_DIRS})
  message(STATUS "studio rooms: no window include in ${MRSIM_ROOMS_DIRS}")
endif()
