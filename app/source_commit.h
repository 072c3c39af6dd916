#pragma once
// The commit rtiow's sources were at when this program was built (cmake/source_commit.cmake,
// run at every build): "4313166c0ffe", with "+changes" where tracked files differed from it,
// or "unknown" outside a git checkout.

namespace rtiow {

const char* source_commit();

}  // namespace rtiow
