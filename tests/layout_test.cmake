# The layout's include rules (README "How the code is laid out"):
#   1. nothing under rig/ includes render/ (the rig knows nothing of rendering);
#   2. the runtime (files directly in rig/) never includes rig/io/ or rig/motion/ (runtime kept apart
#      from offline work, as in ozz-animation);
#   3. the character generators (rig/characters/) never include rig/io/ or rig/motion/ either.
# Run as `cmake -DSOURCE_DIR=... -P layout_test.cmake`; each violation prints one line naming the file,
# the line and the rule, and the script fails. With -DSELF_TEST=ON it checks a scratch tree holding one
# violation of each rule instead, and fails unless all three are caught (so the check cannot pass idly).
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
