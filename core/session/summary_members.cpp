#include "core/session/summary_members.h"

#include "core/render/render_statistics.h"

namespace rtiow {

void write_spp_member(JsonWriter& j, std::uint64_t least, std::uint64_t most, double mean,
                      std::optional<int> asked) {
  j.key("spp").begin_object();
  j.key("least").whole(least);
  j.key("most").whole(most);
  j.key("mean").number(mean);
  asked ? j.key("asked").whole(*asked) : j.key("asked").null();
  j.end();
}

void write_passes_member(JsonWriter& j, const FirstHitPasses& written) {
  j.key("passes").begin_array();
  if (written.albedo) j.string("albedo");
  if (written.normal) j.string("normal");
  if (written.depth) j.string("depth");
  j.end();
}

void write_error_member(JsonWriter& j, ErrorEstimate kind, double estimated,
                        const std::function<void(JsonWriter&)>& target) {
  j.key("error").begin_object();
  kind != ErrorEstimate::None ? j.key("estimated").number(estimated) : j.key("estimated").null();
  j.key("estimate").string(to_string(kind));
  j.key("target");
  target(j);
  j.end();
}

void write_denoise_member(JsonWriter& j, const std::optional<DenoiseFigures>& denoised) {
  j.key("denoise");
  if (!denoised) {
    j.null();
    return;
  }
  j.begin_object();
  j.key("estimated_error").number(denoised->estimated_error);
  j.key("noisy_error").number(denoised->noisy_error);
  j.key("seconds").number(denoised->seconds);
  j.end();
}

}  // namespace rtiow
