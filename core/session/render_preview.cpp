#include "core/session/render_preview.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "core/film/sample_sum.h"
#include "core/io/image_output.h"
#include "core/limits/error.h"
#include "core/render/first_hit_passes.h"
#include "core/render/render_metadata.h"
#include "core/session/tev_display.h"

namespace rtiow {

Checkpointing RenderPreview::watching(const Checkpointing* base, double seconds) {
  Checkpointing watched = base ? *base : Checkpointing{};
  watched.preview_seconds = seconds;
  watched.preview = [this](const RenderState& state) { write(state); };
  return watched;
}

void RenderPreview::write(const RenderState& state) {
  const RenderSettings& s = job_.settings;
  const auto& samples = state.pixels.samples;
  RenderResult so_far;
  so_far.film = Film(film_width(s), film_height(s));
  resolve(state.pixels.sums.color, samples, so_far.film);
  for (std::size_t p = 0; p < samples.size(); ++p) {  // not reached yet (an adaptive first round)
    if (samples[p] == 0)
      so_far.film.at(int(p % std::size_t(film_width(s))), int(p / std::size_t(film_width(s)))) =
          Color(0.0f, 0.0f, 0.0f);
  }
  so_far.pixel_samples = samples;
  so_far.sums.first_hits = state.pixels.sums.first_hits;
  const std::vector<ExtraChannel> passes = pass_channels(so_far, s.passes);
  if (display_) display_->show(so_far.film, passes);
  if (!to_file_) return;
  so_far.rays_traced = state.rays_traced;
  so_far.render_seconds = state.render_seconds;
  so_far.estimated_image_error = state.estimated_image_error;
  so_far.pixels_above_target = state.pixels_above_target;
  so_far.samples_completed =
      samples.empty() ? 0 : int(*std::max_element(samples.begin(), samples.end()));
  Metadata metadata = render_metadata(job_.scene, s, so_far, /*reproducible=*/false);
  const auto* fixed = std::get_if<FixedSamples>(&s.samples);
  const std::string of = fixed ? " of " + std::to_string(fixed->per_pixel) : "";
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", state.render_seconds);
  metadata.emplace_back(metadata_key::kPreview, std::to_string(so_far.samples_completed) + of +
                                                    " spp after " + seconds +
                                                    " s; the render goes on");
  try {
    write_image(job_.output, so_far.film, metadata, passes, frame_placement(s));
    wrote_output_ = true;
  } catch (const std::exception& e) {
    if (!warned_) {
      std::fprintf(stderr, "rtiow: warning: no preview: %s; the render goes on\n",
                   one_line(e.what()).c_str());
      warned_ = true;
    }
  }
}

}  // namespace rtiow
