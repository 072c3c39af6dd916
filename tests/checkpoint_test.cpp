// Checkpoints: a render continued from any state it saved ends with the sums, counts and rays
// of the uninterrupted render, in every sampling mode; the file keeps a state bit for bit,
// and a damaged file or one of another request is refused with a line that says why.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/io/checksum.h"
#include "core/limits/error.h"
#include "core/render/checkpoint_file.h"
#include "core/render/render.h"
#include "core/render/render_state.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene_file/scene_file.h"
#include "tests/test_files.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

RenderSettings small(SamplerKind sampler) {
  RenderSettings s;
  s.width = 40;
  s.height = 27;
  s.samples = FixedSamples{48};
  s.max_depth = 10;
  s.seed = 5;
  s.sampler = sampler;
  return s;
}

void expect_same_render(const RenderResult& a, const RenderResult& b, const std::string& what) {
  ASSERT_EQ(a.sums.size(), b.sums.size()) << what;
  EXPECT_TRUE(a.sums == b.sums) << what << ": the exact sums differ";
  EXPECT_EQ(a.pixel_samples, b.pixel_samples) << what;
  EXPECT_EQ(a.rays_traced, b.rays_traced) << what;
  EXPECT_EQ(a.samples_completed, b.samples_completed) << what;
  EXPECT_EQ(a.estimated_image_error, b.estimated_image_error) << what;
  EXPECT_EQ(a.pixels_above_target, b.pixels_above_target) << what;
  bool spreads_equal = true;
  for (std::size_t p = 0; p < a.sums.spreads.size(); ++p) {
    const PixelSpread &x = a.sums.spreads[p], &y = b.sums.spreads[p];
    spreads_equal = spreads_equal && x == y;
  }
  EXPECT_TRUE(spreads_equal) << what << ": the spreads (variances) differ";
}

// Renders with a save at every chance, keeping a spread of the states saved; then continues
// from each and expects the uninterrupted render.
void expect_resumes_exactly(const RenderSettings& settings, const std::string& what) {
  const Scene scene = make_builtin_scene("cover", 1);
  const RenderResult whole = render(scene, settings);
  std::vector<RenderState> kept;
  int saves = 0;
  Checkpointing checkpointing;
  checkpointing.interval_seconds = 1e-9;  // every pass, every group of an adaptive round
  checkpointing.save = [&](const RenderState& state, SaveReason) {
    ++saves;
    if ((saves & (saves - 1)) == 0 || saves % 37 == 0) kept.push_back(state);
  };
  expect_same_render(whole, render(scene, settings, nullptr, &checkpointing),
                     what + " (saving as it goes)");
  ASSERT_GE(kept.size(), 3u) << what << ": too few states saved to test (" << saves << " saves)";
  for (std::size_t k = 0; k < kept.size(); ++k) {
    Checkpointing resume;
    resume.resume = &kept[k];
    expect_same_render(whole, render(scene, settings, nullptr, &resume),
                       what + ", resumed from state " + std::to_string(k));
  }
}

TEST(Checkpoint, UniformResumesToTheSameBits) {
  for (SamplerKind sampler : {SamplerKind::Independent, SamplerKind::Sobol}) {
    expect_resumes_exactly(small(sampler), "uniform " + to_string(sampler));
  }
  RenderSettings book = small(SamplerKind::Independent);
  book.russian_roulette = false;
  expect_resumes_exactly(book, "uniform, no roulette");
}

TEST(Checkpoint, AdaptiveModesResumeToTheSameBits) {
  RenderSettings s = small(SamplerKind::Sobol);
  s.samples = AdaptiveBudget{48, 4};
  expect_resumes_exactly(s, "--adaptive");
  s.samples = ImageErrorTarget{0.05, 512, 4};
  expect_resumes_exactly(s, "--image-error");
  s.samples = PixelErrorTarget{0.08, 512, 4};
  expect_resumes_exactly(s, "--target-error");
}

// A render whose image could not be written keeps its state from its result: lent, not copied
// (a copy needed the render's memory again, where the write had just run out of it), and a
// resume from the state lent gives the render again.
TEST(Checkpoint, TheStateIsLentOutOfTheResultNotCopied) {
  const Scene scene = make_builtin_scene("cover", 1);
  const RenderSettings s = small(SamplerKind::Sobol);
  RenderResult result = render(scene, s);
  const RenderResult whole = result;
  const void* sums = result.sums.color.data();
  const void* spreads = result.sums.spreads.data();
  const void* samples = result.pixel_samples.data();
  RenderState state = take_state(result);
  EXPECT_EQ(state.pixels.sums.color.data(), sums) << "the sums were copied";
  EXPECT_EQ(state.pixels.sums.spreads.data(), spreads) << "the spreads were copied";
  EXPECT_EQ(state.pixels.samples.data(), samples) << "the counts were copied";
  EXPECT_TRUE(state.pixels.sums == whole.sums);
  EXPECT_EQ(state.pixels.samples, whole.pixel_samples);
  EXPECT_EQ(state.rays_traced, whole.rays_traced);
  // Resumed at its own count, the lent state gives the render it came from.
  RenderState again = state;
  Checkpointing resume;
  resume.resume = &again;
  expect_same_render(whole, render(scene, s, nullptr, &resume), "the lent state resumed");
  restore_state(std::move(state), result);
  EXPECT_EQ(result.sums.color.data(), sums);
  expect_same_render(whole, result, "the state given back");
}

TEST(Checkpoint, FinishedRenderRefinesToTheLargerCount) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s = small(SamplerKind::Sobol);
  RenderState finished{0};
  Checkpointing keep;
  keep.save = [&](const RenderState& state, SaveReason) { finished = state; };
  s.samples = FixedSamples{12};
  render(scene, s, nullptr, &keep);
  s.samples = FixedSamples{40};
  const RenderResult direct = render(scene, s);
  RenderState again = finished;  // the render takes the state it resumes
  Checkpointing resume;
  resume.resume = &finished;
  expect_same_render(direct, render(scene, s, nullptr, &resume), "12 then 40 spp");
  // Fewer than the state holds is refused, naming the count.
  s.samples = FixedSamples{8};
  resume.resume = &again;
  try {
    render(scene, s, nullptr, &resume);
    ADD_FAILURE() << "a state of 12 spp continued to 8";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("already has 12 spp"), std::string::npos) << e.what();
  }
}

class CheckpointFile : public ::testing::Test {
 protected:
  fs::path path_ = fs::path(::testing::TempDir()) /
                   (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                    ".rtiow-checkpoint");
  Scene scene_ = make_builtin_scene("cover", 1);
  RenderSettings settings_ = small(SamplerKind::Sobol);

  // The suite leaves nothing behind in the shared temporary directory.
  void TearDown() override {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }

  RenderState saved_state() {
    RenderState saved{0};
    Checkpointing keep;
    keep.save = [&](const RenderState& state, SaveReason) { saved = state; };
    RenderSettings s = settings_;
    s.samples = AdaptiveBudget{48, 4};
    settings_ = s;
    render(scene_, s, nullptr, &keep);
    return saved;
  }

  // The checkpoint at path_ reads back to `state`, bit for bit.
  void expect_reads_back(const RenderIdentity& id, const RenderState& state) {
    const std::optional<RenderState> read = read_checkpoint(path_.string(), id, settings_);
    ASSERT_TRUE(read);
    EXPECT_TRUE(read->pixels.sums == state.pixels.sums);
    EXPECT_EQ(read->pixels.samples, state.pixels.samples);
    EXPECT_EQ(read->pixels.rays, state.pixels.rays);
    EXPECT_EQ(read->targets, state.targets);
    EXPECT_EQ(read->last_round, state.last_round);
    EXPECT_EQ(read->rays_traced, state.rays_traced);
    EXPECT_EQ(read->render_seconds, state.render_seconds);
    EXPECT_EQ(read->judging_seconds, state.judging_seconds);
    for (std::size_t p = 0; p < state.pixels.sums.spreads.size(); ++p) {
      ASSERT_TRUE(read->pixels.sums.spreads[p] == state.pixels.sums.spreads[p]);
    }
  }

  std::string refusal(const RenderIdentity& identity) {
    try {
      read_checkpoint(path_.string(), identity, settings_);
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(CheckpointFile, KeepsTheStateBitForBit) {
  RenderState state = saved_state();
  state.judging_seconds = state.render_seconds / 3;  // as a denoised error target's would
  const RenderIdentity id = render_identity(scene_, settings_);
  write_checkpoint(path_.string(), id, state);
  expect_reads_back(id, state);
  EXPECT_FALSE(read_checkpoint((path_.string() + ".none"), id, settings_))
      << "no file: nothing to resume";
}

TEST_F(CheckpointFile, RefusesAnotherRequestNamingWhatDiffers) {
  const RenderState state = saved_state();
  write_checkpoint(path_.string(), render_identity(scene_, settings_), state);
  RenderSettings other = settings_;
  other.seed = 6;
  std::string why = refusal(render_identity(scene_, other));
  EXPECT_NE(why.find("seed: the checkpoint's '5', this render's '6'"), std::string::npos) << why;
  other = settings_;
  other.width = 41;
  why = refusal(render_identity(scene_, other));
  EXPECT_NE(why.find("image size"), std::string::npos) << why;
  other = settings_;
  other.sampler = SamplerKind::Independent;
  why = refusal(render_identity(scene_, other));
  EXPECT_NE(why.find("sampler"), std::string::npos) << why;
  other = settings_;
  other.max_depth = 3;
  why = refusal(render_identity(scene_, other));
  EXPECT_NE(why.find("depth"), std::string::npos) << why;
  other = settings_;
  other.russian_roulette = false;  // other paths end: other samples
  why = refusal(render_identity(scene_, other));
  EXPECT_NE(why.find("Russian roulette: the checkpoint's 'on', this render's 'off'"),
            std::string::npos)
      << why;
  other = settings_;
  other.samples = AdaptiveBudget{96, 4};  // an adaptive budget is part of the request
  why = refusal(render_identity(scene_, other));
  EXPECT_NE(why.find("sampling"), std::string::npos) << why;
  const Scene materials = make_builtin_scene("materials", 1);
  why = refusal(render_identity(materials, settings_));
  EXPECT_NE(why.find("scene"), std::string::npos) << why;
}

TEST_F(CheckpointFile, TheSceneDigestTellsApartAnyChangeToTheScene) {
  // The digest takes the spheres and materials as bits, not as text: every field of them,
  // and the settings, still count; a scene read back from its file is the same scene.
  const std::string base = render_identity(scene_, settings_)[IdentityField::Scene];
  EXPECT_EQ(render_identity(parse_scene(scene_to_json(scene_), "c.json"),
                            settings_)[IdentityField::Scene],
            base);
  std::vector<std::pair<std::string, std::function<void(Scene&)>>> changes = {
      {"a centre's x",
       [](Scene& s) { s.spheres.center_x[7] = std::nextafter(s.spheres.center_x[7], 1e9f); }},
      {"a centre's y", [](Scene& s) { s.spheres.center_y[7] += 1; }},
      {"a centre's z", [](Scene& s) { s.spheres.center_z.back() = -s.spheres.center_z.back(); }},
      {"a radius", [](Scene& s) { s.spheres.radius[0] = -s.spheres.radius[0]; }},
      {"a sphere's material",
       [](Scene& s) { std::swap(s.spheres.material[1], s.spheres.material[2]); }},
      {"a sphere more",
       [](Scene& s) {
         s.spheres.add({0, 9, 0}, 1, 0);
       }},
      {"a material's kind",
       [](Scene& s) {
         s.materials[3] = Metal{{0.1f, 0.2f, 0.3f}, 0.05f};
       }},
      {"a glass's Fresnel model",
       [](Scene& s) {
         for (Material& m : s.materials) {
           if (auto* glass = std::get_if<Dielectric>(&m)) {
             glass->fresnel = FresnelModel::Exact;
             return;
           }
         }
       }},
      {"an albedo", [](Scene& s) { std::get<Lambertian>(s.materials[0]).albedo.z = 0.25f; }},
      {"a material more", [](Scene& s) { s.add_material(Dielectric{1.5f}); }},
      {"the background", [](Scene& s) { s.background.zenith.x = 0.4f; }},
      {"the camera", [](Scene& s) { s.camera.vfov_degrees += 1; }},
      {"the name", [](Scene& s) { s.name += "'"; }},
  };
  for (const auto& [what, change] : changes) {
    Scene changed = scene_;
    change(changed);
    EXPECT_NE(render_identity(changed, settings_)[IdentityField::Scene], base) << what;
  }
}

// Formats 2 and 3 named the render in the command line's words of their day ("mode --adaptive
// --min-spp 4 --spp 48", "sampler sobol (one sequence)"): such a header, rebuilt from today's,
// reads as the same render.
std::string older_header(const std::string& today, const std::string& format,
                         const std::string& sampler, const std::string& mode) {
  std::string header = today.substr(0, today.find("end\n") + 4);
  header.replace(0, std::string("rtiow-checkpoint 4").size(), "rtiow-checkpoint " + format);
  const auto line = [&](const std::string& key) {
    const std::size_t at = header.find("\n" + key + " ");
    EXPECT_NE(at, std::string::npos) << key;
    return at + 1;
  };
  const auto drop = [&](const std::string& key) {
    const std::size_t at = line(key);
    header.erase(at, header.find('\n', at) + 1 - at);
  };
  const auto replace = [&](const std::string& key, const std::string& text) {
    const std::size_t at = line(key);
    header.replace(at, header.find('\n', at) - at, text);
  };
  drop("replicates"), drop("roulette");
  replace("sampler", "sampler " + sampler);
  replace("sampling", "mode " + mode);
  if (format == "2") drop("least_samples"), drop("most_samples");
  return header;
}

// A checkpoint of format 2 (fixed little-endian records, 156 bytes a pixel, before the compact
// records) is still read, to the same state: a render kept before resumes after.
TEST_F(CheckpointFile, ReadsAFormat2CheckpointToTheSameState) {
  const RenderState state = saved_state();
  const RenderIdentity id = render_identity(scene_, settings_);
  write_checkpoint(path_.string(), id, state);
  const std::string today = test::slurp(path_);
  std::string bytes =
      older_header(today, "2", "sobol (one sequence)", "--adaptive --min-spp 4 --spp 48");
  const auto put = [&](const auto& v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  };
  const auto put_sum = [&](const PixelSum& sum) {
    for (int c = 0; c < 3; ++c) {
      const auto v = uint128(sum.channel(c));
      put(std::uint64_t(v)), put(std::uint64_t(v >> 64));
    }
  };
  const PixelAccumulators& p = state.pixels;
  for (std::size_t i = 0; i < p.samples.size(); ++i) {
    put_sum(p.sums.color[i]), put_sum(p.sums.spreads[i].squares), put_sum(p.sums.spreads[i].odd);
    put(p.samples[i]), put(p.rays[i]);
    if (!state.targets.empty()) put(state.targets[i]);
  }
  Checksum checksum;
  checksum.update(bytes.data(), bytes.size());
  put(checksum.value());
  test::write_file(path_, bytes);
  expect_reads_back(id, state);
  EXPECT_LT(today.size() * 2, bytes.size()) << "the compact records are not the smaller";
}

// Format 3: today's records under the older header, in each sampling mode it could name.
TEST_F(CheckpointFile, ReadsAFormat3CheckpointInEveryModeItNamed) {
  const RenderState state = saved_state();  // an adaptive budget of 48, at least 4
  write_checkpoint(path_.string(), render_identity(scene_, settings_), state);
  const std::string today = test::slurp(path_);
  const std::string pixels = today.substr(today.find("end\n") + 4);
  const std::string records = pixels.substr(0, pixels.size() - 8);
  const auto with_header = [&](const std::string& header) {
    std::string bytes = header + records;
    Checksum checksum;
    checksum.update(bytes.data(), bytes.size());
    const std::uint64_t sum = checksum.value();
    bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
    test::write_file(path_, bytes);
  };
  with_header(older_header(today, "3", "sobol (one sequence)", "--adaptive --min-spp 4 --spp 48"));
  expect_reads_back(render_identity(scene_, settings_), state);

  // Each older mode and sampler reads as the render it named, and as no other.
  struct Case {
    SampleBudget samples;
    bool roulette;
    std::string sampler, mode;
  };
  const std::vector<Case> cases = {
      {PixelErrorTarget{0.05, 64, 4}, false, "sobol (no roulette)",
       "--target-error 0.05 --min-spp 4 --spp 64"},
      {ImageErrorTarget{0.002, 8192, 16}, true, "sobol",
       "--image-error 0.002 --min-spp 16 --spp 8192"},
      {AdaptiveBudget{std::nullopt, 16}, true, "sobol (one sequence)",
       "--adaptive --min-spp 16 (until the time limit)"},
      {FixedSamples{48}, true, "sobol (one sequence)", "uniform"},
  };
  for (const Case& c : cases) {
    with_header(older_header(today, "3", c.sampler, c.mode));
    const std::optional<CheckpointSummary> read = read_checkpoint_summary(path_.string());
    ASSERT_TRUE(read);
    RenderSettings s = settings_;
    s.samples = c.samples;
    s.russian_roulette = c.roulette;
    const RenderIdentity now = render_identity(scene_, s);
    EXPECT_EQ(identity_mismatch(read->identity, now, "the checkpoint's"), "") << c.mode;
    s.seed += 1;
    EXPECT_NE(identity_mismatch(read->identity, render_identity(scene_, s), "the checkpoint's"), "")
        << c.mode;
  }
  // A mode that does not parse stays as written, and differs by name.
  with_header(older_header(today, "3", "sobol", "--target-error x"));
  const std::string why = identity_mismatch(read_checkpoint_summary(path_.string())->identity,
                                            render_identity(scene_, settings_), "the checkpoint's");
  EXPECT_NE(why.find("sampling: the checkpoint's '--target-error x'"), std::string::npos) << why;
}

TEST_F(CheckpointFile, RefusesDamagedFiles) {
  const RenderState state = saved_state();
  const RenderIdentity id = render_identity(scene_, settings_);
  write_checkpoint(path_.string(), id, state);
  const std::string good = test::slurp(path_);
  const auto refused_with = [&](const std::string& content, const std::string& expected) {
    test::write_file(path_, content);
    const std::string why = refusal(id);
    EXPECT_NE(why.find(expected), std::string::npos) << "got: " << why;
  };
  refused_with(good.substr(0, good.size() / 2), "ends before its pixels do");
  refused_with(good.substr(0, good.size() - 3), "ends before its checksum");
  std::string flipped = good;
  flipped[good.size() / 2] = char(flipped[good.size() / 2] ^ 0x10);
  // A flipped bit is caught by a field's own check or, past them, by the checksum.
  refused_with(flipped, "damaged");
  refused_with(good + "x", "checksum");
  refused_with("", "no checkpoint header");
  refused_with("rtiow-checkpoint 2\nversion 0.1.0\n", "the header does not end");
  refused_with("rtiow-checkpoint 1\nversion 0.1.0\nend\n", "a checkpoint of another format");
}

}  // namespace
}  // namespace rtiow
