#include "core/compare/diff_summary.h"

#include "core/io/summary_json.h"

namespace rtiow {
namespace {

void write_plain(JsonWriter& j, const PlainDiff& p, const PlainThresholds& t) {
  j.begin_object();
  j.key("mean_error").number(p.mean_error);
  j.key("rms_error").number(p.rms_error);
  j.key("max_error").number(p.max_error);
  j.key("worst_pixel").begin_array().whole(p.worst_x).whole(p.worst_y).end();
  j.key("fail_percent").number(p.fail_percent);
  j.key("warn_percent").number(p.warn_percent);
  j.key("thresholds").begin_object();
  j.key("fail").number(t.fail);
  j.key("failpercent").number(t.fail_percent);
  t.hard_fail < 1e300 ? j.key("hardfail").number(t.hard_fail) : j.key("hardfail").null();
  j.key("warn").number(t.warn);
  j.key("warnpercent").number(t.warn_percent);
  j.end().end();
}

void write_noise(JsonWriter& j, const NoiseDiff& n) {
  j.begin_object();
  j.key("renders").whole(n.renders);
  j.key("alpha").number(n.alpha);
  j.key("block_size").whole(n.block_size);
  j.key("blocks").whole(n.blocks);
  j.key("failing_blocks").whole(n.failing_blocks);
  j.key("block_critical_z").number(n.block_critical_z);
  j.key("worst_block_z").number(n.worst_block_z);
  j.key("worst_block").begin_array().whole(n.worst_block_x).whole(n.worst_block_y).end();
  j.key("mean_difference").number(n.mean_difference);
  j.key("mean_difference_error").number(n.mean_difference_error);
  j.key("image_z").number(n.image_z);
  j.key("image_critical_z").number(n.image_critical_z);
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
