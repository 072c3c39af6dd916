#include "app/source_commit.h"

#include "source_commit_value.h"  // generated at every build: RTIOW_SOURCE_COMMIT

namespace rtiow {

const char* source_commit() {
  return RTIOW_SOURCE_COMMIT;
}

}  // namespace rtiow
