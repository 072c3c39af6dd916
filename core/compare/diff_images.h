#pragma once
// Pictures of a comparison (core/compare/image_diff.h), for a user to see where two images
// differ: written with write_image like any render (PNG: gamma 2).

#include "core/compare/image_diff.h"
#include "core/film/film.h"

namespace rtiow {

// |test - reference| per channel, scaled so the largest difference is 1; NaN and infinities
// show as white.
Film difference_image(const DiffInput& test, const DiffInput& reference);

// Each block coloured by its score: red where the test is brighter, blue where darker, full
// at the critical value; dark grey where nothing shows.
Film z_image(const NoiseDiff& d, int width, int height);

// The image itself, as a film (linear values written back as they are; 8-bit ones decoded
// from gamma 2, so that writing it as PNG gives the same picture).
Film to_film(const DiffInput& image);

}  // namespace rtiow
