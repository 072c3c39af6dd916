#include "core/compare/diff_summary.h"

#include "core/io/summary_json.h"

namespace rtiow {
namespace {

// Runs of scalar members go through JsonWriter::members: a whole number as int64, any other
// figure as a double.
void write_plain(JsonWriter& j, const PlainDiff& p, const PlainThresholds& t) {
  j.begin_object();
  j.members({{"mean_error", p.mean_error}, {"rms_error", p.rms_error}, {"max_error", p.max_error}});
  j.key("worst_pixel").begin_array().whole(p.worst_x).whole(p.worst_y).end();
  j.members({{"fail_percent", p.fail_percent}, {"warn_percent", p.warn_percent}});
  j.key("thresholds").begin_object();
  j.members({{"fail", t.fail}, {"failpercent", t.fail_percent}});
  t.hard_fail < 1e300 ? j.key("hardfail").number(t.hard_fail) : j.key("hardfail").null();
  j.members({{"warn", t.warn}, {"warnpercent", t.warn_percent}});
  j.end().end();
}

void write_noise(JsonWriter& j, const NoiseDiff& n) {
  j.begin_object();
  j.members({{"renders", std::int64_t(n.renders)},
             {"alpha", n.alpha},
             {"block_size", std::int64_t(n.block_size)},
             {"blocks", std::int64_t(n.blocks)},
             {"failing_blocks", std::int64_t(n.failing_blocks)},
             {"block_critical_z", n.block_critical_z},
             {"worst_block_z", n.worst_block_z}});
  j.key("worst_block").begin_array().whole(n.worst_block_x).whole(n.worst_block_y).end();
  j.members({{"mean_difference", n.mean_difference},
             {"mean_difference_error", n.mean_difference_error},
             {"image_z", n.image_z},
             {"image_critical_z", n.image_critical_z}});
  j.end();
}

}  // namespace

std::string diff_summary_json(const DiffSummary& d) {
  const bool compared = d.error.empty();
  JsonWriter j = begin_summary("diff", compared ? int(d.verdict) : d.exit_code);
  j.key("reference").string(d.reference);
  j.key("tests").begin_array();
  for (const std::string& test : d.tests) j.string(test);
  j.end();
  j.key("mode").string(d.mode);
  compared ? j.key("width").whole(d.width) : j.key("width").null();
  compared ? j.key("height").whole(d.height) : j.key("height").null();
  j.key("verdict").string(compared ? to_string(d.verdict) : "could not compare");
  compared ? j.key("failure").null() : j.key("failure").string(d.error);
  compared ? j.key("non_finite_pixels").whole(d.non_finite.pixels)
           : j.key("non_finite_pixels").null();
  j.key("plain");
  d.plain&& d.thresholds ? write_plain(j, *d.plain, *d.thresholds) : void(j.null());
  j.key("noise");
  d.noise ? write_noise(j, *d.noise) : void(j.null());
  return summary_text(j);
}

}  // namespace rtiow
