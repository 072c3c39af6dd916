#include "core/compare/diff_summary.h"

#include <nlohmann/json.hpp>

#include "core/io/summary_json.h"

namespace rtiow {

std::string diff_summary_json(const DiffSummary& d) {
  using json = nlohmann::ordered_json;
  const bool compared = d.error.empty();
  json j = summary_head("diff", compared ? int(d.verdict) : d.exit_code);
  j["reference"] = d.reference;
  j["tests"] = d.tests;
  j["mode"] = d.mode;
  j["width"] = compared ? json(d.width) : json();
  j["height"] = compared ? json(d.height) : json();
  j["verdict"] = compared ? to_string(d.verdict) : "could not compare";
  j["failure"] = compared ? json() : json(d.error);
  j["non_finite_pixels"] = compared ? json(d.non_finite.pixels) : json();
  j["plain"] = nullptr;
  j["noise"] = nullptr;
  if (d.plain && d.thresholds) {
    const PlainThresholds& t = *d.thresholds;
    j["plain"] = {{"mean_error", d.plain->mean_error},
                  {"rms_error", d.plain->rms_error},
                  {"max_error", d.plain->max_error},
                  {"worst_pixel", {d.plain->worst_x, d.plain->worst_y}},
                  {"fail_percent", d.plain->fail_percent},
                  {"warn_percent", d.plain->warn_percent},
                  {"thresholds",
                   {{"fail", t.fail},
                    {"failpercent", t.fail_percent},
                    {"hardfail", t.hard_fail < 1e300 ? json(t.hard_fail) : json()},
                    {"warn", t.warn},
                    {"warnpercent", t.warn_percent}}}};
  }
  if (d.noise) {
    const NoiseDiff& n = *d.noise;
    j["noise"] = {{"renders", n.renders},
                  {"alpha", n.alpha},
                  {"block_size", n.block_size},
                  {"blocks", n.blocks},
                  {"failing_blocks", n.failing_blocks},
                  {"block_critical_z", n.block_critical_z},
                  {"worst_block_z", n.worst_block_z},
                  {"worst_block", {n.worst_block_x, n.worst_block_y}},
                  {"mean_difference", n.mean_difference},
                  {"mean_difference_error", n.mean_difference_error},
                  {"image_z", n.image_z},
                  {"image_critical_z", n.image_critical_z}};
  }
  return summary_text(j);
}

}  // namespace rtiow
