#include "core/sampling/sampler.h"

#include "core/limits/error.h"

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

SamplerKind parse_sampler(const std::string& name) {
  for (const SamplerKind kind :
       {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    if (name == to_string(kind)) return kind;
  }
  throw InvalidInput("unknown sampler " + quote_value(name, 40) + " (known: " + sampler_names() +
                     ")");
}

}  // namespace rtiow
