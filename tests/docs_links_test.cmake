# The user's guide holds together: every link in README.md and docs/**.md to a file of the project
# names one that exists, every link to a section (#name, or file.md#name) names a heading of that
# file, and no link leaves the project (the repository stands alone: no ../shared/). Links to the web
# (http:, https:, mailto:) are not followed.
#
# A section's name is its heading as GitHub makes it: lower case, every character but letters,
# digits, spaces, '-' and '_' dropped, spaces made '-', and -1, -2, ... after a repeated one. Bytes
# outside ASCII are dropped too, as GitHub drops symbols like '×'; a heading with an accented letter
# would need that letter kept (none has one today). Lines inside ``` fences are neither headings nor
# links.
#
# Run as `cmake -DSOURCE_DIR=... -P docs_links_test.cmake`; each broken link prints one line naming
# the file, the line and the link, and the script fails. With -DSELF_TEST=ON it checks a scratch tree
# instead holding a missing file, a missing section of another file, a missing section of its own
# file and a link out of the project beside good links (a repeated heading's -1 among them), and
# fails unless exactly those four are caught (so the check cannot pass idly).
cmake_minimum_required(VERSION 3.25)

# The lines of a file as a CMake list, every line kept (empty ones too) so that list positions are line
# numbers: ';', '[' and ']' would split or join a list's elements, so they are read as <SC>, <LB>, <RB>.
function(read_lines file out)
  file(READ "${file}" content)
  string(REPLACE ";" "<SC>" content "${content}")
  string(REPLACE "[" "<LB>" content "${content}")
  string(REPLACE "]" "<RB>" content "${content}")
  string(REPLACE "\n" ";" content "${content}")
  set(${out} "${content}" PARENT_SCOPE)
endfunction()

# Whether `line` opens or closes a ``` fence (`is_fence`), and so whether the lines after it are in one
# (`fenced`, read and set in the caller's scope).
function(fence_line line)
  set(is_fence FALSE PARENT_SCOPE)
  if(line MATCHES "^[ ]*```")
    set(is_fence TRUE PARENT_SCOPE)
    if(fenced)
      set(fenced FALSE PARENT_SCOPE)
    else()
      set(fenced TRUE PARENT_SCOPE)
    endif()
  endif()
endfunction()

# The section names of a Markdown file, into `out`.
function(section_names file out)
  read_lines("${file}" lines)
  set(names "")
  set(fenced FALSE)
  foreach(line IN LISTS lines)
    fence_line("${line}")
    if(is_fence)
      continue()
    endif()
    if(fenced OR NOT line MATCHES "^#+[ ]+(.*)$")
      continue()
    endif()
    string(REGEX REPLACE "<(SC|LB|RB)>" "" name "${CMAKE_MATCH_1}")
    string(TOLOWER "${name}" name)
    string(REGEX REPLACE "[^a-z0-9 _-]" "" name "${name}")
    string(REPLACE " " "-" name "${name}")
    set(slug "${name}")
    set(n 0)
    while(slug IN_LIST names)
      math(EXPR n "${n} + 1")
      set(slug "${name}-${n}")
    endwhile()
    list(APPEND names "${slug}")
  endforeach()
  set(${out} "${names}" PARENT_SCOPE)
endfunction()

# Prints a line for each broken link of the Markdown files under `root` (README.md, docs/**.md) and
# sets `count` to how many.
function(check_links root count)
  file(GLOB_RECURSE docs "${root}/docs/*.md")
  set(files "${root}/README.md" ${docs})
  get_filename_component(root_abs "${root}" ABSOLUTE)
  set(broken 0)
  foreach(file IN LISTS files)
    if(NOT EXISTS "${file}")
      continue()
    endif()
    get_filename_component(dir "${file}" DIRECTORY)
    file(RELATIVE_PATH shown "${root_abs}" "${file}")
    read_lines("${file}" lines)
    set(line_no 0)
    set(fenced FALSE)
    foreach(line IN LISTS lines)
      math(EXPR line_no "${line_no} + 1")
      fence_line("${line}")
      if(is_fence)
        continue()
      endif()
      if(fenced)
        continue()
      endif()
      string(REGEX MATCHALL "<RB>\\([^) ]+\\)" links "${line}")
      foreach(link IN LISTS links)
        string(REGEX REPLACE "^<RB>\\((.*)\\)$" "\\1" target "${link}")
        if(target MATCHES "^(https?|mailto):")
          continue()
        endif()
        set(path "${target}")
        set(anchor "")
        if(target MATCHES "^([^#]*)#(.*)$")
          set(path "${CMAKE_MATCH_1}")
          set(anchor "${CMAKE_MATCH_2}")
        endif()
        set(to "${file}")
        if(NOT path STREQUAL "")
          get_filename_component(to "${dir}/${path}" ABSOLUTE)
          file(RELATIVE_PATH inside "${root_abs}" "${to}")
          if(inside MATCHES "^\\.\\./" OR inside STREQUAL "..")
            message("${shown}:${line_no}: ${target}: leaves the project (the guide must stand alone)")
            math(EXPR broken "${broken} + 1")
            continue()
          endif()
          if(NOT EXISTS "${to}")
            message("${shown}:${line_no}: ${target}: no such file (${inside})")
            math(EXPR broken "${broken} + 1")
            continue()
          endif()
        endif()
        if(NOT anchor STREQUAL "" AND to MATCHES "\\.md$")
          string(MD5 key "${to}")  # each file's sections read once, however many links name it
          if(NOT DEFINED sections_${key})
            section_names("${to}" sections_${key})
          endif()
          if(NOT anchor IN_LIST sections_${key})
            message("${shown}:${line_no}: ${target}: no section \"${anchor}\" in that file")
            math(EXPR broken "${broken} + 1")
          endif()
        endif()
      endforeach()
    endforeach()
  endforeach()
  set(${count} ${broken} PARENT_SCOPE)
endfunction()

if(SELF_TEST)
  set(scratch "${CMAKE_CURRENT_BINARY_DIR}/docs_links_self_test")
  file(REMOVE_RECURSE "${scratch}")
  file(WRITE "${scratch}/README.md"
    "# Guide\n\nSee [the farm](docs/farm.md#a-farm-of-one-node), [again](docs/farm.md#a-farm-of-one-node-1),\n"
    "[nodes](docs/farm.md#nodes--2-slurm); [its status](docs/farm.md#status), [up](#guide), [gone](#lost),\n"
    "[none](docs/none.md), [the web](https://example.com/#x) and [shared](../shared/notes.md).\n"
    "```sh\n# not a heading\n[not a link](nowhere.md)\n```\n")
  file(WRITE "${scratch}/docs/farm.md"
    "# The farm\n\n## A farm of one node\n\ntext [a] [b\n\n## A farm of one node\n\n## Nodes × 2 (Slurm)\n")
  check_links("${scratch}" found)
  file(REMOVE_RECURSE "${scratch}")
  if(NOT found EQUAL 4)
    message(FATAL_ERROR "docs links self-test: expected exactly 4 broken links (a missing file, a missing "
                        "section in another file and in its own, a link out of the project), found ${found}")
  endif()
  message("docs links self-test: the 4 planted broken links were caught")
  return()
endif()

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "docs_links_test.cmake: pass -DSOURCE_DIR=<the project's root>")
endif()
check_links("${SOURCE_DIR}" found)
if(found GREATER 0)
  message(FATAL_ERROR "${found} broken link(s) in README.md and docs/")
endif()
