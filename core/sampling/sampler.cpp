#include "core/sampling/sampler.h"

#include "core/io/error.h"

namespace rtiow {

std::string to_string(SamplerKind kind) {
  return kind == SamplerKind::Independent ? "independent" : "sobol";
}

SamplerKind parse_sampler(const std::string& name) {
  if (name == "independent") return SamplerKind::Independent;
  if (name == "sobol") return SamplerKind::Sobol;
  throw InvalidInput("unknown sampler " + quote_value(name, 40) + " (known: independent, sobol)");
}

}  // namespace rtiow
