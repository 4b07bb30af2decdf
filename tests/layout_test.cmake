# The layout's include rules (docs/code-layout.md). The code is cut into layers by the
# direction of its dependencies, lowest first:
#   rig              the runtime: channels, clips, the rider rig, curve spine, IK, skeleton, pose, skinning
#   rig/characters   the character generators and the seating of a user's rider
#   rig/motion       horse motion: gaits, movements, paths, terrain, crowds, limits, clip analysis
#   rig/mapping      a user's skeleton mapped to the rig's roles: conventions, topology, auto mapping
#   rig/io           files: glTF, JSON and CSV readers and writers
#   scene            the scene document, read in this one place, and its evaluation without pixels
#                    (clip factory, profiles, ridden pairs, evaluator, cameras, bakes)
#   render/image_files  image files read and written, and text drawn (OpenImageIO, in a module)
#   render/tracer    the ray tracer (Embree, the integrator and its lanes, images)
#   render           the shot: evaluated frames traced
#   render/review    review material: movies, layers, sheets, plots, diffs
#   render/farm      rendering on a Slurm cluster
#   cli              the program, every subcommand
# A file may include its own folder and any folder below it, never one above, so the include graph of
# the folders has no cycle. A folder with sources that is not in the list is a violation too (a new
# folder must be given its place). The commands that draw no pixel (STIRRUP_NO_PIXELS: bake, rig,
# clip) include nothing of render/ either.
# The namespace follows the folder too: a file's namespace is stirrup::<its top-level folder> (all of
# rig/** is stirrup::rig, scene/ stirrup::scene, all of render/** stirrup::render, cli/ stirrup::cli),
# so a reader who greps the folder a qualified name says finds it. Every `namespace stirrup...` opening
# line in a source or header must be that namespace or one nested in it (stirrup::rig::pose_transforms);
# a bare `namespace stirrup {` is a violation. Namespaces outside stirrup (anonymous ones, hwy::, a
# third-party forward declaration) are not checked.
# Run as `cmake -DSOURCE_DIR=... -P layout_test.cmake`; each violation prints one line naming the file,
# the line, the include and the two layers (or the namespace found and the one expected), and the
# script fails. With -DSELF_TEST=ON it checks a scratch tree instead holding a planted cycle (rig/ and
# rig/io/ including each other), a tracer file including the review, a library file including the
# program, a scene file including the tracer, a pixel-free command including render/, a folder outside
# the order, a scene header in stirrup::render and a rig header in a bare stirrup namespace, and fails
# unless exactly those eight are caught (so the check cannot pass idly).
#
# With -DCHECK=mirrored_tests it checks instead that tests mirror the source tree file for file: every
# library source, rig/**.cpp, scene/*.cpp and render/**.cpp (not the program, cli/), has its test file
# tests/<the same path>_test.cpp. With -DSELF_TEST=ON as well, a scratch tree with one source lacking
# its test file (and a program file without one, which is allowed) must give exactly that one.
cmake_minimum_required(VERSION 3.25)

set(STIRRUP_LAYERS rig rig/characters rig/motion rig/mapping rig/io scene render/image_files render/tracer render render/review render/farm cli)
set(STIRRUP_NO_PIXELS cli/cmd_bake.cpp cli/cmd_rig.cpp cli/cmd_clip.cpp)

# Appends one line to out_var for every include, in every source and header under `root`'s layers, of a
# project file in a layer above the including file's, for every `namespace stirrup...` line that is not
# the file's top folder's namespace or one nested in it, and for every folder of sources outside the order.
function(check_tree root out_var)
  set(violations)
  file(GLOB_RECURSE all RELATIVE "${root}" "${root}/rig/*.h" "${root}/rig/*.cpp" "${root}/scene/*.h"
       "${root}/scene/*.cpp" "${root}/render/*.h" "${root}/render/*.cpp" "${root}/cli/*.h" "${root}/cli/*.cpp")
  set(unplaced)
  foreach(rel IN LISTS all)
    get_filename_component(folder "${rel}" DIRECTORY)
    list(FIND STIRRUP_LAYERS "${folder}" own)
    if(own EQUAL -1)
      if(NOT folder IN_LIST unplaced)
        list(APPEND unplaced "${folder}")
        list(APPEND violations "${folder}/: a folder of sources with no place in the layer order (tests/layout_test.cmake STIRRUP_LAYERS)")
      endif()
      continue()
    endif()
    string(REGEX REPLACE "/.*" "" top "${folder}")
    set(expected_ns "stirrup::${top}")
    file(STRINGS "${root}/${rel}" lines)
    set(n 0)
    foreach(line IN LISTS lines)
      math(EXPR n "${n} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*\"((rig|scene|render|cli)/[^\"]*)\"")
        set(included "${CMAKE_MATCH_1}")
        get_filename_component(to "${included}" DIRECTORY)
        list(FIND STIRRUP_LAYERS "${to}" other)
        if(other GREATER own)
          list(APPEND violations "${rel}:${n}: #include \"${included}\": ${folder} includes ${to}, a layer above it")
        elseif(rel IN_LIST STIRRUP_NO_PIXELS AND included MATCHES "^render/")
          list(APPEND violations "${rel}:${n}: #include \"${included}\": a command that draws no pixel includes render/")
        endif()
      elseif(line MATCHES "^[ \t]*namespace[ \t]+(stirrup(::[A-Za-z0-9_:]+)?)[ \t]*({|$)")
        set(found_ns "${CMAKE_MATCH_1}")
        string(FIND "${found_ns}::" "${expected_ns}::" at)
        if(NOT at EQUAL 0)
          list(APPEND violations "${rel}:${n}: namespace ${found_ns}: a file under ${top}/ is in ${expected_ns} (or a namespace nested in it)")
        endif()
      endif()
    endforeach()
  endforeach()
  list(LENGTH all n_all)
  if(n_all EQUAL 0)
    list(APPEND violations "${root}: no sources found under rig/, scene/, render/ or cli/ (wrong SOURCE_DIR?)")
  endif()
  set(${out_var} ${violations} PARENT_SCOPE)
endfunction()

# Appends "SOURCE: no test file tests/SOURCE_test.cpp ..." to out_var for every library source under
# `root` without its mirrored test file.
function(check_mirrored_tests root out_var)
  set(missing)
  file(GLOB_RECURSE sources RELATIVE "${root}" "${root}/rig/*.cpp" "${root}/scene/*.cpp" "${root}/render/*.cpp")
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
              tests/render/review/movie_test.cpp cli/cmd_render.cpp)
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
  message(STATUS "layout check: every library source under rig/, scene/ and render/ has its tests/..._test.cpp")
  return()
endif()

if(SELF_TEST)
  string(RANDOM LENGTH 8 tag)
  set(root "${CMAKE_CURRENT_BINARY_DIR}/layout_self_test_${tag}")
  # A cycle: the runtime's pose.h includes a glTF reader that includes pose.h back; only the upward
  # edge is a violation. Then a tracer file including the review (an include indented, spaced), a
  # review file including the program, the scene including the tracer, the bake command including the
  # renderer, and a folder nobody placed. Includes that keep to the order (the reader including the
  # runtime, the shot including the tracer and scene, the bake command the scene) must pass. Then two
  # namespaces that do not follow the folder: a scene header in stirrup::render, a rig header in bare
  # stirrup. Namespaces that do (rig/io in stirrup::rig, a nested stirrup::rig::pose_transforms, the
  # tracer in stirrup::render with Highway's and an anonymous namespace inside, a third-party forward
  # declaration, the program in stirrup::cli) must pass.
  file(MAKE_DIRECTORY "${root}/rig/io" "${root}/scene" "${root}/render/tracer" "${root}/render/review" "${root}/render/extra"
       "${root}/cli")
  file(WRITE "${root}/rig/pose.h" "#pragma once\n#include \"rig/skeleton.h\"\n#include \"rig/io/gltf_clip.h\"\n")
  file(WRITE "${root}/rig/io/gltf_clip.h" "#pragma once\n#include \"rig/pose.h\"\n")
  file(WRITE "${root}/render/tracer/image.cpp" "#include \"render/tracer/image.h\"\n  #  include \"render/review/text.h\"\n")
  file(WRITE "${root}/render/shot.cpp" "#include \"render/tracer/renderer.h\"\n#include \"scene/scene.h\"\n")
  file(WRITE "${root}/scene/view.cpp" "#include \"rig/pose.h\"\n#include \"render/tracer/image.h\"\n")
  file(WRITE "${root}/cli/cmd_bake.cpp" "#include \"scene/scene.h\"\n#include \"render/shot.h\"\n")
  file(WRITE "${root}/render/review/movie.cpp" "#include \"render/shot.h\"\n#include \"cli/options.h\"\n")
  file(WRITE "${root}/render/extra/thing.cpp" "#include \"rig/pose.h\"\n")
  file(WRITE "${root}/scene/camera.h" "#pragma once\nnamespace tinygltf {\nclass Model;\n}\n\nnamespace stirrup::render {\nstruct Camera {};\n}  // namespace stirrup::render\n")
  file(WRITE "${root}/rig/error.h" "#pragma once\n\nnamespace stirrup {\nstruct InputError {};\n}  // namespace stirrup\n")
  file(WRITE "${root}/rig/io/json_fields.h" "#pragma once\n\nnamespace stirrup::rig {\nstruct JsonObjectReader {};\n}  // namespace stirrup::rig\n")
  file(WRITE "${root}/rig/pose_transforms.cpp" "namespace stirrup::rig::pose_transforms {\nnamespace {\n}  // namespace\n}\n")
  file(WRITE "${root}/render/tracer/lanes.cpp" "namespace stirrup::render {\nnamespace {\nint a;\n}\n}\nHWY_BEFORE_NAMESPACE();\nnamespace hwy {\nnamespace HWY_NAMESPACE {\n}\n}\n")
  file(WRITE "${root}/cli/commands.h" "#pragma once\n#include \"scene/scene.h\"\nnamespace stirrup::cli {\nusing namespace stirrup::rig;\n}  // namespace stirrup::cli\n")
  check_tree("${root}" violations)
  file(REMOVE_RECURSE "${root}")
  set(expected
    "cli/cmd_bake.cpp:2: #include \"render/shot.h\": a command that draws no pixel includes render/"
    "render/extra/: a folder of sources with no place in the layer order (tests/layout_test.cmake STIRRUP_LAYERS)"
    "render/review/movie.cpp:2: #include \"cli/options.h\": render/review includes cli, a layer above it"
    "render/tracer/image.cpp:2: #include \"render/review/text.h\": render/tracer includes render/review, a layer above it"
    "rig/error.h:3: namespace stirrup: a file under rig/ is in stirrup::rig (or a namespace nested in it)"
    "rig/pose.h:3: #include \"rig/io/gltf_clip.h\": rig includes rig/io, a layer above it"
    "scene/camera.h:6: namespace stirrup::render: a file under scene/ is in stirrup::scene (or a namespace nested in it)"
    "scene/view.cpp:2: #include \"render/tracer/image.h\": scene includes render/tracer, a layer above it")
  list(SORT violations)
  if(NOT violations STREQUAL expected)
    string(REPLACE ";" "\n  " got "${violations}")
    message(FATAL_ERROR "layout check self-test: expected exactly the 8 planted violations, got:\n  ${got}")
  endif()
  message(STATUS "layout check self-test: the planted cycle and the 7 other planted violations caught, nothing else")
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
  message(FATAL_ERROR "layout check: ${n} include(s) or namespace(s) break the layout's rules")
endif()
message(STATUS "layout check: every include keeps to the layer order ${STIRRUP_LAYERS}, every namespace to its top folder")
