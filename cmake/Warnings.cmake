# rtiow_set_warnings(target): the warning set every target of ours builds with.
function(rtiow_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
endfunction()

# rtiow_set_codegen(target): how hot code is compiled. No -ffast-math: renders must be
# bit-identical across accelerators, and NaN checks must keep working.
function(rtiow_set_codegen target)
  # sqrt need not set errno: lets the naive loop vectorise, changes no result.
  target_compile_options(${target} PRIVATE -fno-math-errno)
  if(RTIOW_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
