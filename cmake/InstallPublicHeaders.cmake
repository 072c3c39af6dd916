# Installs the public API, and only it: core/rtiow.h and what it includes, found by following
# its "core/..." and "materials/..." includes from the source tree when `cmake --install` runs
# (so the set never goes stale). In the source tree the headers are included from the tree's
# root; installed, they live under include/rtiow, with their includes spelt "rtiow/...", so a
# user writes #include <rtiow/rtiow.h> and rtiow takes no generic name ("core/", "materials/")
# in their include path.
#   core/rtiow.h           -> include/rtiow/rtiow.h
#   core/scene/scene.h     -> include/rtiow/scene/scene.h
#   materials/material.h   -> include/rtiow/materials/material.h
# Run by install(CODE) with RTIOW_SOURCE_DIR and RTIOW_STAGING_DIR set.

# The install script runs under old policies: this file's own (IN_LIST) are the project's.
cmake_policy(PUSH)
cmake_policy(VERSION 3.25)

function(rtiow_installed_name source_name out)
  string(REGEX REPLACE "^core/" "rtiow/" name "${source_name}")
  string(REGEX REPLACE "^materials/" "rtiow/materials/" name "${name}")
  set(${out} "${name}" PARENT_SCOPE)
endfunction()

set(pending core/rtiow.h)
set(public)
while(pending)
  list(POP_FRONT pending header)
  if(header IN_LIST public)
    continue()
  endif()
  list(APPEND public ${header})
  file(STRINGS ${RTIOW_SOURCE_DIR}/${header} includes
       REGEX "^[ \t]*#[ \t]*include[ \t]+\"(core|materials)/[^\"]+\"")
  foreach(line ${includes})
    string(REGEX REPLACE ".*\"([^\"]+)\".*" "\\1" included "${line}")
    list(APPEND pending ${included})
  endforeach()
endwhile()

file(REMOVE_RECURSE ${RTIOW_STAGING_DIR})
foreach(header ${public})
  file(READ ${RTIOW_SOURCE_DIR}/${header} text)
  string(REGEX REPLACE "(#[ \t]*include[ \t]+\")core/" "\\1rtiow/" text "${text}")
  string(REGEX REPLACE "(#[ \t]*include[ \t]+\")materials/" "\\1rtiow/materials/" text "${text}")
  rtiow_installed_name(${header} name)
  file(WRITE ${RTIOW_STAGING_DIR}/${name} "${text}")
endforeach()
list(LENGTH public count)
message(STATUS "Public API: ${count} headers")
cmake_policy(POP)
