# rtiow_set_warnings(target): the warning set every target of ours builds with.
function(rtiow_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
endfunction()

# rtiow_set_codegen(target): how hot code is compiled. No -ffast-math: renders must be
# bit-identical across accelerators, and NaN checks must keep working.
function(rtiow_set_codegen target)
  # -ffp-contract=off: GCC fuses a*b+c into an FMA by default in C++ (even in ISO mode), and
  # would do so differently where the same function is inlined into different loops; the
  # Embree callback and the naive loop must round identically.
  # -fno-math-errno: sqrt need not set errno, which lets the naive loop vectorise.
  # -fno-trapping-math: no program of ours enables floating-point traps, so GCC may compute
  # both sides of a select and keep one, which lets branch-free lane loops (the camera's
  # eight rays) vectorise. It changes no value (Clang's default); only the exception flags.
  target_compile_options(${target} PRIVATE -ffp-contract=off -fno-math-errno -fno-trapping-math)
  # Portable unless asked: the hot loops choose their instruction set when the program loads
  # (core/parallel/instruction_sets.h). RTIOW_NATIVE compiles everything for this CPU alone.
  if(RTIOW_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
    target_compile_definitions(${target} PUBLIC RTIOW_NO_DISPATCH)
  endif()
endfunction()
