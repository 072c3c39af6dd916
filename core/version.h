#pragma once
// rtiow's version, written once: in CMakeLists.txt's project(VERSION), compiled into the core.

namespace rtiow {

const char* version();  // "0.1.0"

}  // namespace rtiow
