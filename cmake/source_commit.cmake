# Run at every build (cmake -P): writes OUT, a header defining RTIOW_SOURCE_COMMIT as the
# commit the sources are at ("4313166c0ffe", "+changes" where tracked files differ from it,
# "unknown" outside a git checkout or without git), and rewrites it only when that changes, so
# a build at the same commit compiles nothing again. Configure time would go stale at the
# next commit.
find_program(git_program git)
set(commit "unknown")
if(git_program)
  execute_process(COMMAND ${git_program} -C ${SOURCE} rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE head RESULT_VARIABLE failed ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT failed AND head)
    set(commit ${head})
    execute_process(COMMAND ${git_program} -C ${SOURCE} status --porcelain --untracked-files=no
                    OUTPUT_VARIABLE changes RESULT_VARIABLE failed ERROR_QUIET)
    if(NOT failed AND changes)
      string(APPEND commit "+changes")
    endif()
  endif()
endif()
set(text "#define RTIOW_SOURCE_COMMIT \"${commit}\"\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE ${OUT} "${text}")
endif()
