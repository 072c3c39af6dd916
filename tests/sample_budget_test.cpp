// What --spp means is decided once, in resolve(), and said in a type: these tests hold each
// request to the budget it must become, and each budget to its own checks.

#include "core/render/sample_budget.h"

#include <gtest/gtest.h>

#include <string>
#include <variant>

#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/render/render_request.h"
#include "core/render/sample_share.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

SampleBudget budget_of(const RenderRequest& request) {
  return resolve(make_builtin_scene("materials", 1), request).settings.samples;
}

std::string refusal(const RenderSettings& settings) {
  try {
    validate(settings);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SampleBudget, ResolveSaysWhichMeaningTheCountHas) {
  RenderRequest r;
  const int scene_spp = make_builtin_scene("materials", 1).image.samples_per_pixel;
  EXPECT_EQ(std::get<FixedSamples>(budget_of(r)).per_pixel, scene_spp);
  r.spp = 64;
  EXPECT_EQ(std::get<FixedSamples>(budget_of(r)).per_pixel, 64);
  r.adaptive = true, r.min_samples = 8;
  const auto budget = std::get<AdaptiveBudget>(budget_of(r));
  EXPECT_EQ(budget.per_pixel, 64);
  EXPECT_EQ(budget.least, 8);
  r.adaptive = false, r.image_error = 0.05;
  const auto image = std::get<ImageErrorTarget>(budget_of(r));
  EXPECT_EQ(image.error, 0.05);
  EXPECT_EQ(image.most, 64) << "with an error target, --spp is the cap";
  r.image_error = 0, r.target_error = 0.1, r.spp.reset();
  const auto pixel = std::get<PixelErrorTarget>(budget_of(r));
  EXPECT_EQ(pixel.most, kDefaultErrorDrivenMaxSpp);
  // With only a time limit: passes until it, or (with --adaptive) the time as the budget.
  r = RenderRequest{};
  r.time_limit_seconds = 1;
  EXPECT_TRUE(std::holds_alternative<UntilTimeLimit>(budget_of(r)));
  r.adaptive = true;
  EXPECT_FALSE(std::get<AdaptiveBudget>(budget_of(r)).per_pixel);
  r.spp = 32;
  EXPECT_EQ(std::get<AdaptiveBudget>(budget_of(r)).per_pixel, 32) << "both bound it";
}

TEST(SampleBudget, EachMeaningHasItsOwnChecks) {
  RenderSettings s;
  s.width = 8, s.height = 8, s.max_depth = 8;  // settings as render() has them: resolved
  s.samples = FixedSamples{0};
  EXPECT_NE(refusal(s).find("spp must be > 0"), std::string::npos) << refusal(s);
  s.samples = UntilTimeLimit{};
  EXPECT_NE(refusal(s).find("needs a time limit"), std::string::npos) << refusal(s);
  s.time_limit_seconds = 1;
  EXPECT_EQ(refusal(s), "accepted");
  s.time_limit_seconds = 0;
  s.samples = AdaptiveBudget{std::nullopt};
  EXPECT_NE(refusal(s).find("an AdaptiveBudget needs a budget"), std::string::npos) << refusal(s);
  s.samples = AdaptiveBudget{16, 16};
  EXPECT_NE(refusal(s).find("leaves nothing to allocate"), std::string::npos) << refusal(s);
  s.samples = PixelErrorTarget{0.0, 64};
  EXPECT_NE(refusal(s).find("target error must be"), std::string::npos) << refusal(s);
  s.samples = ImageErrorTarget{0.05, 64, 1};
  EXPECT_NE(refusal(s).find("minimum samples must be >= 2"), std::string::npos) << refusal(s);
  // Only a fixed count can be cut into shares.
  s.samples = ImageErrorTarget{0.05, 64};
  EXPECT_THROW(shareable_samples(s, "--part"), InvalidInput);
  s.samples = FixedSamples{64};
  EXPECT_EQ(shareable_samples(s, "--part"), 64u);
  s.first_sample = 8, s.samples = AdaptiveBudget{64};
  EXPECT_NE(refusal(s).find("a share of a render"), std::string::npos) << refusal(s);
}

// The core names a setting by the library's name; a front end that spells it otherwise says
// so once, and the same refusal then reads in its words.
TEST(SampleBudget, RefusalsNameSettingsInTheAskersWords) {
  RenderRequest r;
  r.min_samples = 1, r.adaptive = true;
  const auto refusal_of = [&] {
    try {
      resolve(make_builtin_scene("materials", 1), r);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal_of().find("min_spp must be >= 2"), std::string::npos) << refusal_of();
  r.min_samples = 4, r.adaptive = false;
  EXPECT_NE(refusal_of().find("min_spp=4 applies to adaptive sampling (target_error, "
                              "image_error or adaptive)"),
            std::string::npos)
      << refusal_of();
  spell_settings_as([](std::string_view name, std::string_view value) {
    std::string text = "<";
    text.append(name);
    if (!value.empty()) text.append(":").append(value);
    return text.append(">");
  });
  const std::string spelt = refusal_of();
  spell_settings_as(nullptr);  // the library's own again
  EXPECT_NE(spelt.find("<min_spp:4> applies to adaptive sampling (<target_error>, "
                       "<image_error> or <adaptive>)"),
            std::string::npos)
      << spelt;
  EXPECT_EQ(setting("spp", "8"), "spp=8");
}

}  // namespace
}  // namespace rtiow
