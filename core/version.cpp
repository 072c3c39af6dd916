#include "core/version.h"

namespace rtiow {

const char* version() {
  return RTIOW_VERSION;  // from project(VERSION), defined by core/CMakeLists.txt
}

}  // namespace rtiow
