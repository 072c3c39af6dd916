#pragma once
// rtiow's version, written once: in CMakeLists.txt's project(VERSION), compiled into the core.
// A change that moves a render's bits raises it: a checkpoint resumes, and parts merge, only
// under the version that began them (0.2.0: the Russian roulette; 0.3.0: Sobol's joint point over
// three bounces).

namespace rtiow {

const char* version();  // "0.3.0"

}  // namespace rtiow
