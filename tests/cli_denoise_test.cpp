// `--denoise` and `rtiow denoise` from outside: what the files hold, that a render denoised at
// once and one kept as parts and denoised after its merge give the same pixels, and the
// refusals.

#include <oneapi/tbb/task_arena.h>

#include <atomic>
#include <mutex>

#include "core/render/part_merge.h"
#include "core/render/render_part.h"
#include "tests/cli_helpers.h"

namespace rtiow::test::cli {
namespace {

const char* const kSmall = "--width 64 --height 40 --spp 8 --seed 3";

TEST(CliDenoise, WritesTheDenoisedImageTheNoisyOneAndTheEstimatedError) {
  const fs::path image = output_path("denoised.exr"), summary = output_path("summary.json");
  const CommandResult r = run_rtiow("render --denoise " + std::string(kSmall) + " -o " +
                                    image.string() + " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("denoised in "), std::string::npos) << r.stderr_text;
  for (const char* channel : {"noisy.R", "denoise.mse.G", "denoise.kept", "albedo.R", "N.Z", "Z"})
    EXPECT_FALSE(exr_channel(image, channel).empty()) << channel;
  const std::vector<float> noisy = exr_channel(image, "noisy.R");
  int width = 0, height = 0;
  const std::vector<float> rgb = exr_pixels(image, width, height);
  ASSERT_EQ(rgb.size(), noisy.size() * 3);
  double differ = 0;
  for (std::size_t p = 0; p < noisy.size(); ++p) differ += rgb[3 * p] != noisy[p];
  EXPECT_GT(differ, 0.5 * double(noisy.size())) << "the image is the noisy one";
  const auto j = nlohmann::json::parse(slurp(summary));
  ASSERT_TRUE(j["denoise"].is_object()) << j.dump();
  EXPECT_GT(j["denoise"]["estimated_error"].get<double>(), 0.0);
  EXPECT_LT(j["denoise"]["estimated_error"].get<double>(),
            j["denoise"]["noisy_error"].get<double>());
  EXPECT_EQ(summary_schema_violations({summary}), "");
  auto in = OIIO::ImageInput::open(image.string());
  ASSERT_TRUE(in);
  EXPECT_NEAR(in->spec().get_float_attribute("rtiow:denoise.estimated_error"),
              j["denoise"]["estimated_error"].get<double>(), 1e-6);
}

TEST(CliDenoise, PartsDenoisedAfterTheirMergeGiveTheRendersPixels) {
  const fs::path whole = output_path("whole.exr"), merged = output_path("merged.exr");
  const fs::path a = output_path("a.exr"), b = output_path("b.exr");
  // Taller than the 64 rows a part is read by at a time, and not a multiple of them.
  const std::string args = "render -q --denoise --width 24 --height 150 --spp 8 --seed 3";
  ASSERT_EQ(run_rtiow(args + " --threads 1 -o " + whole.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(args + " --part 0/2 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(args + " --part 1/2 -o " + b.string()).exit_code, 0);
  const CommandResult r =
      run_rtiow("denoise " + a.string() + " " + b.string() + " -o " + merged.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("merged 2 parts: "), std::string::npos) << r.stderr_text;
  {  // It says the merged sums' error, as a render's line does (the file's metadata holds it).
    auto in = OIIO::ImageInput::open(merged.string());
    ASSERT_TRUE(in);
    const float error = in->spec().get_float_attribute("rtiow:estimated_image_error", -1.0f);
    ASSERT_GT(error, 0.0f);
    char said[64];
    std::snprintf(said, sizeof said, ", 8 spp, image error %.3g estimated", double(error));
    EXPECT_NE(r.stderr_text.find(said), std::string::npos) << said << "\n" << r.stderr_text;
  }
  // A whole render kept for later is one part.
  const fs::path kept = output_path("kept.exr"), single = output_path("single.png");
  ASSERT_EQ(run_rtiow(args + " --part 0/1 -o " + kept.string()).exit_code, 0);
  const CommandResult one_part = run_rtiow("denoise " + kept.string() + " -o " + single.string());
  ASSERT_EQ(one_part.exit_code, 0) << one_part.stderr_text;
  EXPECT_NE(one_part.stderr_text.find("merged 1 part: "), std::string::npos)
      << one_part.stderr_text;
  int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
  const std::vector<float> one = exr_pixels(whole, w1, h1), two = exr_pixels(merged, w2, h2);
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(one, two);
  EXPECT_EQ(exr_channel(whole, "denoise.mse.R"), exr_channel(merged, "denoise.mse.R"));
  // What a display follows of it: the parts' rows read, strip by strip, and the denoiser.
  rtiow::WorkProgress reading, denoising;
  std::vector<std::uint64_t> seen;
  std::mutex seen_lock;  // asked from the denoiser's threads at once
  rtiow::MergeRequest request;
  request.denoise = true, request.reading = &reading, request.denoising = &denoising;
  request.cancelled = [&] {  // asked by the denoiser: the parts are read by then
    const std::lock_guard<std::mutex> hold(seen_lock);
    seen.push_back(reading.done.load());
    return false;
  };
  const rtiow::MergedImage image = rtiow::merge_part_files({a.string(), b.string()}, request);
  EXPECT_EQ(reading.total.load(), 2 * rtiow::PartMerge::kPartWork);
  EXPECT_EQ(reading.done.load(), reading.total.load());
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.front(), reading.total.load());
  EXPECT_GT(denoising.total.load(), 0u);
  EXPECT_EQ(denoising.done.load(), denoising.total.load());
  EXPECT_EQ(image.film.pixels().size(), std::size_t(24 * 150));
}

TEST(CliDenoise, LikeRendersADenoisedImageAgainDenoised) {
  const fs::path first = output_path("first.png"), again = output_path("again.png");
  ASSERT_EQ(run_rtiow("render -q --reproducible --denoise " + std::string(kSmall) + " -o " +
                      first.string())
                .exit_code,
            0);
  const CommandResult r = run_rtiow("render -q --like " + first.string() + " -o " + again.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(first), slurp(again));
}

TEST(CliDenoise, AnImageErrorTargetJudgesTheDenoisedImage) {
  const fs::path image = output_path("target.exr"), summary = output_path("target.json");
  const fs::path again = output_path("again.exr");
  const std::string args = "--width 64 --height 40 --seed 3 --image-error 0.15 --denoise";
  const CommandResult r = run_rtiow("render --reproducible " + args + " -o " + image.string() +
                                    " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(" spp (denoised image error 0.15)"), std::string::npos)
      << r.stderr_text;
  const auto j = nlohmann::json::parse(slurp(summary));
  EXPECT_EQ(j["error"]["target"]["kind"], "denoised image") << j.dump();
  EXPECT_TRUE(j["error"]["target"]["reached"].get<bool>()) << j.dump();
  EXPECT_EQ(j["error"]["estimated"], j["denoise"]["estimated_error"]) << j.dump();
  EXPECT_LE(j["denoise"]["estimated_error"].get<double>(), 0.15);
  EXPECT_EQ(j["spp"]["least"], j["spp"]["most"]) << j.dump();
  // Its judgements' denoising is part of its time but not of its rate (the rate over the whole
  // time read 1.1 Mrays/s where the rays were traced at about 12).
  const double seconds = j["render_seconds"].get<double>();
  const double judging = j["judging_seconds"].get<double>();
  EXPECT_GT(judging, 0.0) << j.dump();
  EXPECT_LT(judging, seconds) << j.dump();
  EXPECT_DOUBLE_EQ(j["mrays_per_second"].get<double>(),
                   j["rays"].get<double>() / (seconds - judging) * 1e-6)
      << j.dump();
  EXPECT_NE(r.stderr_text.find(" s of it denoising), "), std::string::npos) << r.stderr_text;
  EXPECT_EQ(summary_schema_violations({summary}), "");
  // The image records its target: --like renders it again, to the same bytes.
  const CommandResult like =
      run_rtiow("render -q --reproducible --like " + image.string() + " -o " + again.string());
  ASSERT_EQ(like.exit_code, 0) << like.stderr_text;
  EXPECT_EQ(slurp(image), slurp(again));
}

// A target its time limit cut short reports the error of the image it delivers, wherever the
// limit fell: the summary line, --summary-json and the metadata give the denoised image's
// estimate (they gave the last judgement's, of fewer samples, or none).
TEST(CliDenoise, ATargetCutShortReportsTheErrorOfTheImageItDelivers) {
  const fs::path image = output_path("cut.exr"), summary = output_path("cut.json");
  const CommandResult r =
      run_rtiow("render --width 96 --seed 3 --image-error 0.001 --denoise --time-limit 0.3 -o " +
                image.string() + " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto j = nlohmann::json::parse(slurp(summary));
  EXPECT_FALSE(j["error"]["target"]["reached"].get<bool>()) << j.dump();
  EXPECT_EQ(j["error"]["estimate"], "calibrated") << j.dump();
  EXPECT_EQ(j["error"]["estimated"], j["denoise"]["estimated_error"]) << j.dump();
  const double delivered = j["denoise"]["estimated_error"].get<double>();
  auto in = OIIO::ImageInput::open(image.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().get_float_attribute("rtiow:estimated_image_error", -1.0f),
            in->spec().get_float_attribute("rtiow:denoise.estimated_error", -2.0f));
  char said[64];
  std::snprintf(said, sizeof said, "not reached: %.3g at ", delivered);
  EXPECT_NE(r.stderr_text.find(said), std::string::npos) << said << "\n" << r.stderr_text;
}

TEST(CliDenoise, ARenderStoppedBeforeTwoSamplesKeepsItsNoisyImage) {
  // A time limit that ends the render after its first pass of 1 spp: nothing to compare.
  const fs::path image = output_path("first-pass.png");
  const CommandResult r =
      run_rtiow("render --denoise --time-limit 0.000001 --width 32 -o " + image.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(fs::exists(image));
  EXPECT_NE(r.stderr_text.find("warning: the image is not denoised: a pixel has fewer than one "
                               "sample in each half"),
            std::string::npos)
      << r.stderr_text;
}

// A render farm's node denoises the merged frame beside other work: --threads caps the merge and
// the denoiser as it caps a render, and the image is the same bytes on any count.
TEST(CliDenoise, ThreadsCapTheMergeAndTheDenoiser) {
  const fs::path kept = output_path("kept.exr");
  ASSERT_EQ(
      run_rtiow("render -q --denoise " + std::string(kSmall) + " --part 0/1 -o " + kept.string())
          .exit_code,
      0);
  const fs::path every = output_path("every.exr");
  ASSERT_EQ(run_rtiow("denoise -q " + kept.string() + " -o " + every.string()).exit_code, 0);
  for (const char* threads : {"1", "3"}) {
    const fs::path capped = output_path(std::string("capped-") + threads + ".exr");
    const CommandResult r = run_rtiow("denoise -q --threads " + std::string(threads) + " " +
                                      kept.string() + " -o " + capped.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_EQ(slurp(capped), slurp(every)) << "--threads " << threads;
  }
  // The denoiser's loops run in an arena of the count asked (its stop is asked from them).
  for (const int threads : {1, 3}) {
    std::atomic<int> widest{0};
    MergeRequest request;
    request.denoise = true, request.threads = threads;
    request.cancelled = [&] {
      const int here = oneapi::tbb::this_task_arena::max_concurrency();
      for (int seen = widest.load(); here > seen && !widest.compare_exchange_weak(seen, here);) {
      }
      return false;
    };
    merge_part_files({kept.string()}, request);
    EXPECT_EQ(widest.load(), threads);
  }
  // A count out of range is refused in one line, before anything is read or written.
  for (const std::string& command :
       {std::string("denoise --threads -1 "), std::string("merge --denoise --threads 5000 ")}) {
    const fs::path out = output_path("refused.png");
    const CommandResult r = run_rtiow(command + kept.string() + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
    EXPECT_EQ(count_lines(r.stderr_text), 1) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("--threads must be from 0 (all cores) to 1024"), std::string::npos)
        << r.stderr_text;
    EXPECT_FALSE(fs::exists(out));
  }
}

// A farm's script reads the merged frame's figures from --summary-json, as a render's: the same
// keys in the same shapes (one writer for each: core/session/summary_members.h), the figures the
// lines and the file's metadata give, in the published schema.
TEST(CliDenoise, MergeAndDenoiseWriteTheSummaryARenderWrites) {
  const fs::path a = output_path("a.exr"), b = output_path("b.exr");
  const std::string args = "render -q --denoise " + std::string(kSmall);
  ASSERT_EQ(run_rtiow(args + " --part 0/2 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(args + " --part 1/2 -o " + b.string()).exit_code, 0);
  const fs::path image = output_path("denoised.exr"), summary = output_path("denoised.json");
  const CommandResult r =
      run_rtiow("denoise --threads 1 " + a.string() + " " + b.string() + " -o " + image.string() +
                " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(summary_schema_violations({summary}), "");
  const auto j = nlohmann::json::parse(slurp(summary));
  EXPECT_EQ(j["command"], "denoise");
  EXPECT_EQ(j["exit_code"], 0);
  EXPECT_EQ(j["output"], image.string());
  EXPECT_EQ(j["parts"], nlohmann::json::array({a.string(), b.string()}));
  EXPECT_EQ(j["width"], 64);
  EXPECT_EQ(j["height"], 40);
  EXPECT_TRUE(j["crop"].is_null());
  EXPECT_EQ(j["passes"], nlohmann::json::array({"albedo", "normal", "depth"}));
  EXPECT_EQ(j["threads"], 1);
  EXPECT_EQ(j["spp"]["least"], 8);
  EXPECT_EQ(j["spp"]["most"], 8);
  EXPECT_TRUE(j["spp"]["asked"].is_null());
  EXPECT_EQ(j["error"]["estimate"], "calibrated");
  EXPECT_TRUE(j["error"]["target"].is_null());
  auto in = OIIO::ImageInput::open(image.string());
  ASSERT_TRUE(in);
  const double merged_error = j["error"]["estimated"].get<double>();
  EXPECT_NEAR(in->spec().get_float_attribute("rtiow:estimated_image_error"), merged_error,
              1e-6 * merged_error);
  const double denoised_error = j["denoise"]["estimated_error"].get<double>();
  EXPECT_NEAR(in->spec().get_float_attribute("rtiow:denoise.estimated_error"), denoised_error,
              1e-6 * denoised_error);
  char said[64];
  std::snprintf(said, sizeof said, "image error %.4f estimated (the noisy image %.4f",
                denoised_error, j["denoise"]["noisy_error"].get<double>());
  EXPECT_NE(r.stderr_text.find(said), std::string::npos) << said << "\n" << r.stderr_text;

  // A plain merge to a format without the passes: no denoiser's figures, no passes written.
  const fs::path png = output_path("merged.png"), plain = output_path("merged.json");
  ASSERT_EQ(run_rtiow("merge -q " + a.string() + " " + b.string() + " -o " + png.string() +
                      " --summary-json " + plain.string())
                .exit_code,
            0);
  const auto m = nlohmann::json::parse(slurp(plain));
  EXPECT_EQ(m["command"], "merge");
  EXPECT_TRUE(m["denoise"].is_null());
  EXPECT_EQ(m["passes"], nlohmann::json::array());
  EXPECT_EQ(m["error"], j["error"]);

  // A crop's parts: the frame and the region, as the render's summary says them.
  const fs::path crop = output_path("crop.exr"), crop_render = output_path("crop-render.json");
  ASSERT_EQ(run_rtiow(args + " --crop 8,4,40,30 --part 0/1 -o " + crop.string() +
                      " --summary-json " + crop_render.string())
                .exit_code,
            0);
  const fs::path crop_merged = output_path("crop-merged.exr"), crop_json = output_path("crop.json");
  ASSERT_EQ(run_rtiow("merge -q " + crop.string() + " -o " + crop_merged.string() +
                      " --summary-json " + crop_json.string())
                .exit_code,
            0);
  const auto rendered = nlohmann::json::parse(slurp(crop_render));
  const auto merged = nlohmann::json::parse(slurp(crop_json));
  for (const char* key : {"width", "height", "crop", "passes", "error"})
    EXPECT_EQ(merged[key], rendered[key]) << key;
  EXPECT_EQ(summary_schema_violations({plain, crop_json}), "");

  // Neither a part nor the image may take the summary's name.
  for (const fs::path& taken : {a, png}) {
    const std::string before = slurp(taken);
    const CommandResult refused = run_rtiow("merge " + a.string() + " " + b.string() + " -o " +
                                            png.string() + " --summary-json " + taken.string());
    EXPECT_EQ(refused.exit_code, 2) << refused.stderr_text;
    EXPECT_EQ(count_lines(refused.stderr_text), 1) << refused.stderr_text;
    EXPECT_EQ(slurp(taken), before);
  }
}

TEST(CliDenoise, RefusesWhatItCannotDenoiseInOneLine) {
  expect_refused("--denoise --target-error 0.05", "the target would be each noisy pixel's error");
  expect_refused("--denoise --spp 1", "--denoise needs at least 2 spp");
  // A count no render takes is refused as the plain render refuses it.
  expect_refused("--denoise --spp -5", "spp must be > 0");
  expect_refused("--denoise --spp 0", "spp must be > 0");
  // Parts rendered without --denoise keep no halves or first hits.
  const fs::path part = output_path("plain.exr"), out = output_path("out.png");
  ASSERT_EQ(
      run_rtiow("render -q " + std::string(kSmall) + " --part 0/1 -o " + part.string()).exit_code,
      0);
  const CommandResult r = run_rtiow("denoise " + part.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_EQ(count_lines(r.stderr_text), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("render them with --denoise"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(out));
  // Not a part: an image.
  const fs::path image = output_path("image.exr");
  ASSERT_EQ(run_rtiow("render -q " + std::string(kSmall) + " -o " + image.string()).exit_code, 0);
  const CommandResult not_part = run_rtiow("denoise " + image.string() + " -o " + out.string());
  EXPECT_EQ(not_part.exit_code, 2) << not_part.stderr_text;
  EXPECT_EQ(count_lines(not_part.stderr_text), 1) << not_part.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace rtiow::test::cli
