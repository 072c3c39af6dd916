#include "core/version.h"

#include <embree3/rtcore_config.h>
#include <oneapi/tbb/version.h>

namespace rtiow {

// RTIOW_VERSION, RTIOW_BUILD_TYPE, RTIOW_OPTIMISATION and RTIOW_OIIO_VERSION are defined by
// core/CMakeLists.txt from what CMake configured.
const char* version() {
  return RTIOW_VERSION;
}

namespace {

std::string instruction_sets() {
#if defined(RTIOW_NO_DISPATCH)
  return "compiled for the building machine's CPU alone (-march=native)";
#elif defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  // As the hot loops' target_clones choose (core/parallel/instruction_sets.h).
  __builtin_cpu_init();
  const char* level = __builtin_cpu_supports("x86-64-v4")   ? "x86-64-v4"
                      : __builtin_cpu_supports("x86-64-v3") ? "x86-64-v3"
                                                            : "x86-64";
  return std::string("hot loops for x86-64, x86-64-v3 and x86-64-v4, chosen at start: ") + level +
         " on this CPU";
#else
  return "the compiler's default for this machine (no choice at start)";
#endif
}

}  // namespace

std::vector<std::string> build_facts() {
  // Each fact appended piece by piece to a named string: GCC 12 warns falsely
  // (-Wstringop-overflow) on chains of operator+ over temporaries once they are inlined into a
  // link-time optimised test program.
  std::string compiler = "compiler: ";
#if defined(__clang__)
  compiler.append("Clang ");
#elif defined(__GNUC__)
  compiler.append("GCC ");
#endif
  compiler.append(__VERSION__).append(", C++20, ").append(RTIOW_BUILD_TYPE).append(" build");
  std::string optimisation = "optimisation: ";
  optimisation.append(RTIOW_OPTIMISATION);
  std::string sets = "instruction sets: ";
  sets.append(instruction_sets());
  std::string libraries = "libraries: Embree ";
  libraries.append(RTC_VERSION_STRING).append(", oneTBB ").append(TBB_VERSION_STRING);
  libraries.append(" (loaded: ").append(TBB_runtime_version()).append("), OpenImageIO ");
  libraries.append(RTIOW_OIIO_VERSION)
      .append(" (the image backend, loaded for formats other than PNG)");
  return {compiler, optimisation, sets, libraries};
}

}  // namespace rtiow
