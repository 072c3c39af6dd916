#include "core/render/first_hit_passes.h"

#include <array>
#include <cstddef>

#include "core/film/first_hit_sum.h"
#include "core/limits/error.h"
#include "core/limits/nearest_name.h"
#include "core/render/render_settings.h"

namespace rtiow {
namespace {

// Each pass: its name, where it lives in FirstHitPasses, and its channels among a
// FirstHitSum's (core/film/first_hit_sum.h), with the names they take in a file.
struct PassInfo {
  const char* name;
  bool FirstHitPasses::*asked;
  std::size_t first_channel;
  std::vector<const char*> channel_names;
};

const std::array<PassInfo, 3>& pass_table() {
  static const std::array<PassInfo, 3> table{
      PassInfo{"albedo", &FirstHitPasses::albedo, 0, {"albedo.R", "albedo.G", "albedo.B"}},
      PassInfo{"normal", &FirstHitPasses::normal, 3, {"N.X", "N.Y", "N.Z"}},
      PassInfo{"depth", &FirstHitPasses::depth, 6, {"Z"}}};
  return table;
}

}  // namespace

std::string to_string(const FirstHitPasses& passes) {
  std::string text;
  for (const PassInfo& pass : pass_table()) {
    if (!(passes.*pass.asked)) continue;
    if (!text.empty()) text += ",";
    text += pass.name;
  }
  return text.empty() ? "none" : text;
}

std::string pass_names() {
  std::string text;
  // Appended piece by piece: GCC 12 under LTO took `"" + std::string` for an overflow.
  for (const PassInfo& pass : pass_table()) {
    if (!text.empty()) text += ", ";
    text += pass.name;
  }
  return text;
}

FirstHitPasses parse_passes(const std::string& list) {
  FirstHitPasses passes;
  if (list == "none") return passes;
  std::vector<std::string> known;
  for (const PassInfo& pass : pass_table()) known.emplace_back(pass.name);
  std::size_t at = 0;
  while (true) {
    const std::size_t comma = list.find(',', at);
    const std::string name = list.substr(at, comma == std::string::npos ? comma : comma - at);
    const PassInfo* found = nullptr;
    for (const PassInfo& pass : pass_table()) {
      if (name == pass.name) found = &pass;
    }
    if (!found) {
      throw InvalidInput("unknown pass " + quote_value(name) + did_you_mean(name, known) +
                         " (known: " + pass_names() + "; a list is written albedo,normal,depth)");
    }
    if (passes.*found->asked) throw InvalidInput("pass " + quote_value(name) + " is given twice");
    passes.*found->asked = true;
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return passes;
}

std::vector<std::string> pass_channel_names(const FirstHitPasses& passes) {
  std::vector<std::string> names;
  for (const PassInfo& pass : pass_table()) {
    if (passes.*pass.asked)
      names.insert(names.end(), pass.channel_names.begin(), pass.channel_names.end());
  }
  return names;
}

std::vector<ExtraChannel> pass_channels(const RenderResult& result, const FirstHitPasses& passes) {
  std::vector<ExtraChannel> channels;
  if (!passes.any()) return channels;
  if (result.sums.first_hits.size() != result.pixel_samples.size()) {
    throw std::invalid_argument("a render without first-hit sums has no passes to write");
  }
  for (const PassInfo& pass : pass_table()) {
    if (!(passes.*pass.asked)) continue;
    for (std::size_t i = 0; i < pass.channel_names.size(); ++i) {
      ExtraChannel channel{pass.channel_names[i], {}};
      channel.values.reserve(result.sums.first_hits.size());
      for (std::size_t p = 0; p < result.sums.first_hits.size(); ++p) {
        channel.values.push_back(
            result.sums.first_hits[p].mean(pass.first_channel + i, result.pixel_samples[p]));
      }
      channels.push_back(std::move(channel));
    }
  }
  return channels;
}

}  // namespace rtiow
