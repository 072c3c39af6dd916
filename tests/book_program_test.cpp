// rtiow's expected image is the book's, block by block: the book's own program (tests/book/,
// v3.2.3's code with its own random numbers) and rtiow render one small scene with a fuzzy
// metal, glass and a diffuse ball, and every 8x8 block's mean agrees within what both report as
// their noise. The comparison can see a change of model: the later edition's fuzzy metal (a unit
// vector where the book takes a point in the ball) fails it in several blocks.
//
// What it can see (64x36, 1024 spp each side, 40 blocks x 3 channels, Bonferroni at
// family-wise 0.001: |z| > 4.6): a block's standard error is 0.1-0.3% of its value, so a
// difference of about 1.5% in one block, or 0.5% over a whole quarter of the image, fails it.
// The later edition's metal differs by up to 2.1% per block (10 blocks beyond, |z| up to 9).
// A 0.025% difference in the image mean (issue 42) is far below it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "core/render/render.h"
#include "core/render/render_statistics.h"
#include "core/scene/scene.h"
#include "tests/launch.h"

namespace rtiow {
namespace {

constexpr int kWidth = 64, kHeight = 36, kSpp = 1024, kBlock = 8;

// The scene tests/book/book_moments.cc builds with the book's classes.
Scene book_comparison_scene() {
  Scene s;
  s.spheres.add({0.0f, -100.5f, -1.0f}, 100.0f, s.add_material(Lambertian{{0.5f, 0.5f, 0.5f}}));
  s.spheres.add({-1.05f, 0.0f, -1.2f}, 0.5f, s.add_material(Lambertian{{0.1f, 0.2f, 0.5f}}));
  s.spheres.add({0.15f, 0.0f, -1.5f}, 0.5f, s.add_material(Dielectric{1.5f}));
  s.spheres.add({0.9f, -0.1f, -0.9f}, 0.4f, s.add_material(make_metal({0.8f, 0.6f, 0.2f}, 0.6f)));
  s.camera.lookfrom = {0, 0.3, 0.6};
  s.camera.lookat = {0, -0.05, -1};
  s.camera.vfov_degrees = 70.0;
  s.image = ImageSettings{kWidth, double(kWidth) / kHeight, kSpp, 50};
  return s;
}

// Each pixel's mean and the variance of that mean, per channel, rows from the top.
struct Moments {
  std::vector<double> mean, variance;
};

Moments book_program(std::uint64_t seed, const char* metal, int spp = kSpp,
                     const char* binary = BOOK_MOMENTS_BINARY, int depth = 50) {
  const std::string out = std::string(RTIOW_TEST_OUTPUT_DIR) + "/book-" + metal + "-" +
                          std::to_string(seed) + ".moments";
  rtiow::test::Launch command;
  command.argv = {binary,
                  std::to_string(kWidth),
                  std::to_string(kHeight),
                  std::to_string(spp),
                  std::to_string(seed),
                  metal,
                  out,
                  std::to_string(depth)};
  EXPECT_EQ(rtiow::test::launch(command), 0) << binary;
  std::vector<double> records(std::size_t(kWidth * kHeight * 6));
  std::ifstream in(out, std::ios::binary);
  in.read(reinterpret_cast<char*>(records.data()), std::streamsize(records.size() * 8));
  EXPECT_TRUE(in) << "short " << out;
  std::remove(out.c_str());
  Moments m;
  for (std::size_t p = 0; p < records.size(); p += 6) {
    for (std::size_t c = 0; c < 3; ++c) {
      m.mean.push_back(records[p + c]);
      m.variance.push_back(records[p + 3 + c]);
    }
  }
  return m;
}

Moments rtiow_render(SamplerKind sampler, int spp = kSpp, int depth = 50) {
  const Scene scene = book_comparison_scene();
  RenderSettings s;
  s.width = kWidth;
  s.height = kHeight;
  s.samples = FixedSamples{spp};
  s.max_depth = depth;
  s.sampler = sampler;
  s.estimate_error = true;  // the variance of each pixel's mean, honest for every sampler
  s.seed = 7;
  const RenderResult r = render(scene, s);
  const std::vector<Vec3d> variances = pixel_mean_variances(r);
  Moments m;
  for (std::size_t p = 0; p < variances.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      m.mean.push_back(double(r.film.pixels()[p][c]));
      m.variance.push_back(variances[p][c]);
    }
  }
  return m;
}

// |z| beyond which a standard normal lies with probability `alpha` (two-sided).
double two_sided_threshold(double alpha) {
  double low = 0, high = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = (low + high) / 2;
    (std::erfc(mid / std::sqrt(2.0)) > alpha ? low : high) = mid;
  }
  return low;
}

// The blocks (and channels) whose means differ beyond Bonferroni's threshold at family-wise
// 0.001, and the largest |z|. A block-channel with no variance on either side (the sky's blue
// is 1 on every path) is compared exactly.
struct BlockVerdict {
  int beyond = 0;
  double largest = 0;
};

BlockVerdict compare_blocks(const Moments& a, const Moments& b) {
  struct Block {
    double a = 0, b = 0, variance = 0;
    int pixels = 0;
  };
  const int columns = (kWidth + kBlock - 1) / kBlock, rows = (kHeight + kBlock - 1) / kBlock;
  std::vector<Block> blocks(std::size_t(columns * rows * 3));
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int c = 0; c < 3; ++c) {
        const auto i = std::size_t((y * kWidth + x) * 3 + c);
        Block& block = blocks[std::size_t(((y / kBlock) * columns + x / kBlock) * 3 + c)];
        block.a += a.mean[i], block.b += b.mean[i];
        block.variance += a.variance[i] + b.variance[i];
        ++block.pixels;
      }
    }
  }
  const double threshold = two_sided_threshold(0.001 / double(blocks.size()));
  BlockVerdict verdict;
  for (const Block& block : blocks) {
    const double n = block.pixels, difference = (block.a - block.b) / n;
    const double z = block.variance > 0 ? difference / (std::sqrt(block.variance) / n)
                     : difference == 0  ? 0.0
                                        : INFINITY;
    verdict.largest = std::max(verdict.largest, std::abs(z));
    verdict.beyond += std::abs(z) > threshold;
  }
  return verdict;
}

TEST(BookProgram, RtiowEqualsTheBookBlockByBlockForEverySampler) {
  const Moments book = book_program(1, "book");
  for (const SamplerKind sampler : {SamplerKind::Independent, SamplerKind::Sobol}) {
    const BlockVerdict v = compare_blocks(rtiow_render(sampler), book);
    std::printf("rtiow (%s) against the book: %d blocks beyond, largest |z| %.2f\n",
                to_string(sampler).c_str(), v.beyond, v.largest);
    EXPECT_EQ(v.beyond, 0) << to_string(sampler);
  }
}

// The comparison's power: the book's program with the later edition's metal against itself
// with the book's, and against rtiow.
TEST(BookProgram, TheComparisonSeesTheLaterEditionsMetal) {
  const Moments later = book_program(3, "later");
  const BlockVerdict books = compare_blocks(later, book_program(2, "book"));
  const BlockVerdict with_rtiow = compare_blocks(later, rtiow_render(SamplerKind::Sobol));
  std::printf(
      "later edition's metal: %d blocks beyond against the book (|z| up to %.1f), %d "
      "against rtiow (%.1f)\n",
      books.beyond, books.largest, with_rtiow.beyond, with_rtiow.largest);
  EXPECT_GE(books.beyond, 3);
  EXPECT_GE(with_rtiow.beyond, 3);
}

// The mean over independent runs (seeds far apart: glibc's rand() streams of nearby seeds are
// linearly related, so the runs of seeds 1, 2, 3, ... are not independent).
Moments book_average(const char* binary, int runs, int spp, int depth) {
  Moments total;
  for (int run = 0; run < runs; ++run) {
    const Moments m = book_program(0x9e3779b97f4a7c15u * std::uint64_t(run + 1) >> 33, "book", spp,
                                   binary, depth);
    if (total.mean.empty()) total.mean.assign(m.mean.size(), 0.0), total.variance = total.mean;
    for (std::size_t i = 0; i < m.mean.size(); ++i) {
      total.mean[i] += m.mean[i] / runs;
      total.variance[i] += m.variance[i] / (double(runs) * runs);
    }
  }
  return total;
}

// The image mean per channel of a against b, relative, and its z.
void compare_means(const Moments& a, const Moments& b, double relative[3], double z[3]) {
  for (std::size_t c = 0; c < 3; ++c) {
    double sa = 0, sb = 0, variance = 0;
    for (std::size_t i = c; i < a.mean.size(); i += 3) {
      sa += a.mean[i], sb += b.mean[i], variance += a.variance[i] + b.variance[i];
    }
    relative[c] = (sa - sb) / sb;
    z[c] = (sa - sb) / std::sqrt(variance);
  }
}

// The 0.025% by which rtiow's cover was brighter than the book's program (issue 42) is the
// program's random numbers: glibc's rand() is an additive lagged-Fibonacci generator whose
// draws are linearly related, and the book's own image comes out darker than its model. With
// mt19937_64 in its place (nothing else changed) the book's program agrees with rtiow in the
// image mean and in every block. Measured here (8 x 16384 spp of the book, 131072 of rtiow):
// rtiow - book (mt19937_64) +0.0003 / +0.0002 / -0.0004% at depth 50 (z 0.2 / 0.1 / -0.3),
// +0.0014% at depth 2 (z 0.7); book (rand) - book (mt19937_64) at depth 2 -0.019 / -0.020 /
// -0.023% (z -8.7 / -9.6 / -10.6). An independent tracer (numpy, double, PCG64) agrees with
// rtiow too (docs/accuracy.md). 150 s of CPU, so not in the suite: build/bin/book_tests
// --gtest_also_run_disabled_tests --gtest_filter='*ImageMean*'.
TEST(BookProgram, DISABLED_TheImageMeanIsTheBooksModelOnceItsGeneratorIsSound) {
  constexpr int kRuns = 8, kBookSpp = 16384, kRtiowSpp = kRuns * kBookSpp;
  double relative[3], z[3];
  for (const int depth : {50, 2}) {
    const Moments rtiow = rtiow_render(SamplerKind::Independent, kRtiowSpp, depth);
    const Moments sound = book_average(BOOK_MOMENTS_MT19937_BINARY, kRuns, kBookSpp, depth);
    compare_means(rtiow, sound, relative, z);
    for (std::size_t c = 0; c < 3; ++c) {
      std::printf("depth %d, channel %zu: rtiow - book (mt19937_64) %+.4f%% (z %+.2f)\n", depth, c,
                  100 * relative[c], z[c]);
      EXPECT_LT(std::abs(z[c]), 3.0) << "depth " << depth;
    }
    EXPECT_EQ(compare_blocks(rtiow, sound).beyond, 0) << "depth " << depth;
    if (depth != 2) continue;
    // At depth 2 (one diffuse bounce to the sky) the generator's bias is largest.
    compare_means(book_average(BOOK_MOMENTS_BINARY, kRuns, kBookSpp, depth), sound, relative, z);
    for (std::size_t c = 0; c < 3; ++c) {
      std::printf("depth 2, channel %zu: book (rand) - book (mt19937_64) %+.4f%% (z %+.2f)\n", c,
                  100 * relative[c], z[c]);
      EXPECT_LT(z[c], -5.0) << "the book's rand() no longer darkens its image";
    }
  }
}

}  // namespace
}  // namespace rtiow
