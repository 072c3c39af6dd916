#pragma once
// rtiow's version, written once: in CMakeLists.txt's project(VERSION), compiled into the core.
// A change that moves a render's bits raises it: a checkpoint resumes, and parts merge, only
// under the version that began them (0.2.0: the Russian roulette; 0.3.0: Sobol's joint point over
// three bounces). Beside it, what this build of the core is made of, as `rtiow --version` says.

#include <string>
#include <vector>

namespace rtiow {

const char* version();  // "0.3.0"

// What was built in, one fact a line ("compiler: GCC 12.2.0, C++20, Release"): the compiler
// and build type, the optimisation (a profile or none), the instruction sets of the hot loops
// and the one this CPU runs, and the libraries' versions (Embree, oneTBB as built and as
// loaded, the OpenImageIO of the image backend). The command line adds its own (MPI).
std::vector<std::string> build_facts();

}  // namespace rtiow
