#include "core/version.h"

#include <embree3/rtcore_config.h>
#include <oneapi/tbb/version.h>

#include <cstdio>
#include <string>
#include <vector>

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
  // Literals joined by the compiler and one snprintf per fact with a run-time part: GCC 12 warns
  // falsely (-Wstringop-overflow) on std::string appends of these once they are inlined into a
  // link-time optimised program.
#if defined(__clang__)
#define RTIOW_COMPILER "Clang "
#else
#define RTIOW_COMPILER "GCC "
#endif
  char sets[256], libraries[512];
  std::snprintf(sets, sizeof sets, "instruction sets: %s", instruction_sets().c_str());
  std::snprintf(libraries, sizeof libraries,
                "libraries: Embree " RTC_VERSION_STRING ", oneTBB " TBB_VERSION_STRING
                " (loaded: %s), OpenImageIO " RTIOW_OIIO_VERSION
                " (the image backend, loaded for formats other than PNG)",
                TBB_runtime_version());
  return {"compiler: " RTIOW_COMPILER __VERSION__ ", C++20, " RTIOW_BUILD_TYPE " build",
          "optimisation: " RTIOW_OPTIMISATION, sets, libraries};
#undef RTIOW_COMPILER
}

}  // namespace rtiow
