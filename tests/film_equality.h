#pragma once
// Bit-for-bit equality of two films: determinism is the one place tests compare exactly.

#include <cstring>

#include "core/film/film.h"

namespace rtiow::test {

inline bool bit_identical(const Film& a, const Film& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Color)) == 0;
}

}  // namespace rtiow::test
