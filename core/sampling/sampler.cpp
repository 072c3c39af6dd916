#include "core/sampling/sampler.h"

#include "core/limits/error.h"
#include "core/limits/nearest_name.h"

namespace rtiow {

std::string to_string(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::Independent:
      return "independent";
    case SamplerKind::Sobol:
      return "sobol";
    default:
      return "padded-sobol";
  }
}

const char* sampler_names() {
  return "independent, sobol, padded-sobol";
}

namespace {
constexpr SamplerKind kSamplerKinds[] = {SamplerKind::Independent, SamplerKind::Sobol,
                                         SamplerKind::PaddedSobol};
}  // namespace

std::vector<std::string> sampler_name_list() {
  std::vector<std::string> names;
  for (const SamplerKind kind : kSamplerKinds) names.push_back(to_string(kind));
  return names;
}

SamplerKind parse_sampler(const std::string& name) {
  for (const SamplerKind kind : kSamplerKinds) {
    if (name == to_string(kind)) return kind;
  }
  throw InvalidInput("unknown sampler " + quote_value(name, 40) +
                     did_you_mean(name, sampler_name_list()) + " (known: " + sampler_names() + ")");
}

}  // namespace rtiow
