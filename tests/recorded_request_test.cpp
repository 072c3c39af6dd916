// An image's recorded request, through the library: read back, it asks for the render that
// made the image, and a caller's part replaces the image's whole part and nothing else.

#include "core/render/recorded_request.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "core/io/image_output.h"
#include "core/limits/error.h"
#include "core/render/render.h"
#include "core/render/render_identity.h"
#include "core/render/render_job.h"
#include "core/render/render_metadata.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

class RecordedRequestTest : public ::testing::Test {
 protected:
  fs::path image_ = fs::path(::testing::TempDir()) / "recorded_request.png";
  void TearDown() override {
    std::error_code ignored;
    fs::remove(image_, ignored);
  }

  // Renders `job` as `rtiow render` would and writes it with its metadata.
  RenderJob render_to_image(const JobRequest& job, bool reproducible) {
    RenderJob prepared = prepare_job(job);
    const RenderResult result = render(prepared.scene, prepared.settings);
    write_image(image_.string(), result.film,
                render_metadata(prepared.scene, prepared.settings, result, reproducible));
    return prepared;
  }
};

TEST_F(RecordedRequestTest, AnImageAsksForTheRenderThatMadeIt) {
  JobRequest job;
  job.scene = "spheres:20", job.scene_seed = 7;
  job.request.width = 24, job.request.spp = 3, job.request.seed = 11;
  job.request.max_depth = 9, job.request.russian_roulette = false;
  job.request.sampler = SamplerKind::Independent;
  job.request.camera.vfov_degrees = 33.5;
  const RenderJob made = render_to_image(job, true);

  const RecordedRequest image = read_recorded_request(image_.string(), "image");
  EXPECT_TRUE(image.reproducible);
  bool reproducible = false;
  JobRequest again = overlay_recorded(image, JobRequest{}, {}, false, reproducible);
  EXPECT_TRUE(reproducible);
  const RenderJob remade = prepare_job(again);
  EXPECT_EQ(remade.scene.name, made.scene.name);
  EXPECT_EQ(remade.settings.width, made.settings.width);
  EXPECT_EQ(remade.settings.height, made.settings.height);
  EXPECT_EQ(remade.settings.seed, 11u);
  EXPECT_EQ(remade.settings.max_depth, 9);
  EXPECT_FALSE(remade.settings.russian_roulette);
  EXPECT_EQ(remade.settings.sampler, SamplerKind::Independent);
  EXPECT_EQ(remade.scene.camera.vfov_degrees, 33.5);
  EXPECT_NO_THROW(check_scene_of_image(image, make_builtin_scene("spheres:20", 7)));
  EXPECT_THROW(check_scene_of_image(image, make_builtin_scene("spheres:20", 8)), InvalidInput);

  // The caller's seed and vfov are theirs; the rest is still the image's.
  JobRequest mine;
  mine.request.seed = 3;
  mine.request.camera.vfov_degrees = 50;
  again =
      overlay_recorded(image, mine, {RequestPart::Seed, RequestPart::Vfov}, false, reproducible);
  const RenderJob changed = prepare_job(again);
  EXPECT_EQ(changed.settings.seed, 3u);
  EXPECT_EQ(changed.scene.camera.vfov_degrees, 50);
  EXPECT_EQ(changed.settings.max_depth, 9);
  EXPECT_EQ(changed.scene.camera.lookfrom.x, made.scene.camera.lookfrom.x);
}

TEST_F(RecordedRequestTest, WhatNoRenderRepeatsIsRefusedUnlessTheCallerGivesIt) {
  JobRequest job;
  job.scene = "materials";
  job.request.width = 16, job.request.adaptive = true, job.request.time_limit_seconds = 0.5;
  render_to_image(job, false);
  const RecordedRequest image = read_recorded_request(image_.string(), "image 'x'");
  bool reproducible = false;
  try {
    overlay_recorded(image, JobRequest{}, {}, false, reproducible);
    ADD_FAILURE() << "a time limit's budget was repeated";
  } catch (const InvalidInput& e) {
    // Its budget was the time limit, or the limit stopped it (on a loaded machine): either
    // way where each pixel stopped depends on the clock.
    const std::string why = e.what();
    EXPECT_TRUE(why.find("image 'x': its adaptive budget was a time limit") != std::string::npos ||
                why.find("image 'x': its adaptive render was stopped early") != std::string::npos)
        << why;
  }
  JobRequest mine;
  mine.request.spp = 4;
  const JobRequest again =
      overlay_recorded(image, mine, {RequestPart::Samples}, false, reproducible);
  EXPECT_EQ(again.request.spp, 4);
  EXPECT_FALSE(again.request.adaptive);
  EXPECT_FALSE(reproducible) << "the image recorded its time: it was not reproducible";
}

// The image's metadata carries the render's identity: each field the identity table gives a
// metadata key is written from the identity, and the request read back makes a render of the
// same identity, field for field (a crop, the passes, seeds past 2^63 and a sampler, depth and
// roulette other than the defaults).
TEST_F(RecordedRequestTest, TheImageCarriesTheRenderIdentity) {
  JobRequest job;
  job.scene = "spheres:12", job.scene_seed = 18446744073709551614ull;
  job.request.width = 32, job.request.height = 20, job.request.spp = 2;
  job.request.seed = 18446744073709551615ull;  // the largest: above what an int64 holds
  job.request.max_depth = 7, job.request.russian_roulette = false;
  job.request.sampler = SamplerKind::Independent;
  job.request.crop = PixelRegion{4, 3, 20, 15};
  job.request.passes = parse_passes("albedo,depth");
  for (const char* name : {"identity.png", "identity.exr"}) {
    image_ = fs::path(::testing::TempDir()) / name;
    job.output = (fs::path(::testing::TempDir()) / "unwritten.exr").string();
    job.output_given = true;
    const RenderJob made = render_to_image(job, true);
    const RenderIdentity identity = render_identity(made.scene, made.settings);
    const RenderResult result = render(made.scene, made.settings);
    const Metadata metadata = render_metadata(made.scene, made.settings, result, true);
    for (const IdentityFieldDeclaration& d : kIdentityFields) {
      if (!d.metadata_key) continue;
      const auto entry = std::find_if(metadata.begin(), metadata.end(),
                                      [&](const auto& e) { return e.first == d.metadata_key; });
      ASSERT_NE(entry, metadata.end()) << d.metadata_key;
      EXPECT_EQ(*entry, identity_metadata(identity, d.field)) << d.metadata_key;
    }
    const RecordedRequest image = read_recorded_request(image_.string(), "image");
    bool reproducible = false;
    JobRequest asked;
    asked.output = job.output, asked.output_given = true;
    const RenderJob remade = prepare_job(overlay_recorded(image, asked, {}, true, reproducible));
    const RenderIdentity again = render_identity(remade.scene, remade.settings);
    for (const IdentityFieldDeclaration& d : kIdentityFields) {
      EXPECT_EQ(again[d.field], identity[d.field]) << name << ": " << d.label;
    }
    TearDown();
  }
}

}  // namespace
}  // namespace rtiow
