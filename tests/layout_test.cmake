# The layout's include rules (README "How the code is laid out"):
#   1. nothing under rig/ includes render/ (the rig knows nothing of rendering);
#   2. the runtime (files directly in rig/) never includes rig/io/ or rig/motion/ (runtime kept apart
#      from offline work, as in ozz-animation);
#   3. the character generators (rig/characters/) never include rig/io/ or rig/motion/ either.
# Run as `cmake -DSOURCE_DIR=... -P layout_test.cmake`; each violation prints one line naming the file,
# the line and the rule, and the script fails. With -DSELF_TEST=ON it checks a scratch tree holding one
# violation of each rule instead, and fails unless all three are caught (so the check cannot pass idly).
#
# With -DCHECK=mirrored_tests it checks instead that tests mirror the source tree file for file: every
# library source, rig/**.cpp and render/**.cpp but the program's own render/cli/, has its test file
# tests/<the same path>_test.cpp. With -DSELF_TEST=ON as well, a scratch tree with one source lacking
# its test file (and a program file without one, which is allowed) must give exactly that one.
cmake_minimum_required(VERSION 3.25)

# Appends "FILE:LINE: RULE" to out_var for every include in `files` (relative to `root`) that matches
# `pattern`.
function(find_includes root files pattern rule out_var)
  set(found ${${out_var}})
  foreach(rel ${files})
    file(STRINGS "${root}/${rel}" lines)
    set(n 0)
    foreach(line IN LISTS lines)
      math(EXPR n "${n} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*\"(${pattern})")
        list(APPEND found "${rel}:${n}: ${rule} (#include \"${CMAKE_MATCH_1}...\")")
      endif()
    endforeach()
  endforeach()
  set(${out_var} ${found} PARENT_SCOPE)
endfunction()

function(check_tree root out_var)
  set(violations)
  file(GLOB_RECURSE rig_all RELATIVE "${root}" "${root}/rig/*.h" "${root}/rig/*.cpp")
  file(GLOB runtime RELATIVE "${root}" "${root}/rig/*.h" "${root}/rig/*.cpp")
  file(GLOB_RECURSE characters RELATIVE "${root}" "${root}/rig/characters/*.h" "${root}/rig/characters/*.cpp")
  find_includes("${root}" "${rig_all}" "render/" "rig/ includes render/" violations)
  find_includes("${root}" "${runtime}" "rig/io/|rig/motion/" "the rig runtime includes offline code" violations)
  find_includes("${root}" "${characters}" "rig/io/|rig/motion/" "a character generator includes offline code" violations)
  list(LENGTH runtime n_runtime)
  if(n_runtime EQUAL 0)
    list(APPEND violations "${root}/rig: no runtime sources found (wrong SOURCE_DIR?)")
  endif()
  set(${out_var} ${violations} PARENT_SCOPE)
endfunction()

# Appends "SOURCE: no test file tests/SOURCE_test.cpp ..." to out_var for every library source under
# `root` without its mirrored test file.
function(check_mirrored_tests root out_var)
  set(missing)
  file(GLOB_RECURSE sources RELATIVE "${root}" "${root}/rig/*.cpp" "${root}/render/*.cpp")
  list(FILTER sources EXCLUDE REGEX "^render/cli/")  # the program: tested end to end by tests/render/cli/
  foreach(src IN LISTS sources)
    string(REGEX REPLACE "\\.cpp$" "_test.cpp" test "${src}")
    if(NOT EXISTS "${root}/tests/${test}")
      list(APPEND missing "${src}: no test file tests/${test} (tests mirror the source tree file for file)")
    endif()
  endforeach()
  list(LENGTH sources n)
  if(n EQUAL 0)
    list(APPEND missing "${root}: no library sources found (wrong SOURCE_DIR?)")
  endif()
  set(${out_var} ${missing} PARENT_SCOPE)
endfunction()

if(CHECK STREQUAL "mirrored_tests")
  if(SELF_TEST)
    string(RANDOM LENGTH 8 tag)
    set(root "${CMAKE_CURRENT_BINARY_DIR}/layout_mirror_self_test_${tag}")
    foreach(f rig/pose.cpp tests/rig/pose_test.cpp rig/io/gltf_clip.cpp render/review/movie.cpp
              tests/render/review/movie_test.cpp render/cli/cmd_render.cpp)
      get_filename_component(d "${root}/${f}" DIRECTORY)
      file(MAKE_DIRECTORY "${d}")
      file(WRITE "${root}/${f}" "// scratch\n")
    endforeach()
    check_mirrored_tests("${root}" missing)
    file(REMOVE_RECURSE "${root}")
    set(expected "rig/io/gltf_clip.cpp: no test file tests/rig/io/gltf_clip_test.cpp (tests mirror the source tree file for file)")
    if(NOT missing STREQUAL expected)
      message(FATAL_ERROR "mirrored-tests self-test: expected only rig/io/gltf_clip.cpp reported, got: ${missing}")
    endif()
    message(STATUS "mirrored-tests self-test: the source without a test file caught, the program's file left alone")
    return()
  endif()
  if(NOT SOURCE_DIR)
    message(FATAL_ERROR "layout_test.cmake: pass -DSOURCE_DIR=<the project's source folder>")
  endif()
  check_mirrored_tests("${SOURCE_DIR}" missing)
  if(missing)
    foreach(m IN LISTS missing)
      message("${m}")
    endforeach()
    list(LENGTH missing n)
    message(FATAL_ERROR "layout check: ${n} library source(s) without their test file")
  endif()
  message(STATUS "layout check: every library source under rig/ and render/ has its tests/..._test.cpp")
  return()
endif()

if(SELF_TEST)
  string(RANDOM LENGTH 8 tag)
  set(root "${CMAKE_CURRENT_BINARY_DIR}/layout_self_test_${tag}")
  file(MAKE_DIRECTORY "${root}/rig/io" "${root}/rig/characters")
  file(WRITE "${root}/rig/pose.cpp" "#include \"rig/pose.h\"\n#include \"rig/io/gltf_clip.h\"\n")
  file(WRITE "${root}/rig/io/gltf_clip.cpp" "#include \"rig/io/gltf_clip.h\"\n  #  include \"render/image.h\"\n")
  file(WRITE "${root}/rig/characters/tube.cpp" "#include \"rig/mesh.h\"\n#include \"rig/motion/noise.h\"\n")
  check_tree("${root}" violations)
  file(REMOVE_RECURSE "${root}")
  list(LENGTH violations n)
  if(NOT n EQUAL 3)
    message(FATAL_ERROR "layout check self-test: expected 3 violations in the scratch tree, found ${n}: ${violations}")
  endif()
  message(STATUS "layout check self-test: all 3 planted violations caught")
  return()
endif()

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "layout_test.cmake: pass -DSOURCE_DIR=<the project's source folder>")
endif()
check_tree("${SOURCE_DIR}" violations)
if(violations)
  foreach(v IN LISTS violations)
    message("${v}")
  endforeach()
  list(LENGTH violations n)
  message(FATAL_ERROR "layout check: ${n} include(s) break the layout's rules")
endif()
message(STATUS "layout check: rig/ includes no render/; the rig runtime and characters include no rig/io/ or rig/motion/")
