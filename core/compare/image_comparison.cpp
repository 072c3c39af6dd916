#include "core/compare/image_comparison.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/image_size.h"
#include "core/limits/setting_name.h"

namespace rtiow {
namespace {

// Refuses, before reading them, more images of the reference's size than half of this
// machine's memory holds (each read image keeps R, G, B and their variances as floats).
void check_memory_for(std::size_t images, const DiffInput& reference) {
  const std::uint64_t per_image =
      std::uint64_t(reference.width) * std::uint64_t(reference.height) * 6 * sizeof(float);
  const std::uint64_t available = physical_memory_bytes();
  if (per_image * images > available / 2) {
    throw InvalidInput(
        std::to_string(images) + " images of " + std::to_string(reference.width) + "x" +
        std::to_string(reference.height) + " need " + std::to_string((per_image * images) >> 20) +
        " MiB, more than half of this machine's " + std::to_string(available >> 20) + " MiB");
  }
}

// auto: several tests -> seeds; one, both with variances -> noise; otherwise plain.
std::string chosen_mode(const std::string& mode, const DiffInput& reference,
                        const std::vector<DiffInput>& tests) {
  const bool several = tests.size() > 1;
  const bool variances = !reference.variance.empty() && !tests[0].variance.empty();
  if (mode == "auto") return several ? "seeds" : variances ? "noise" : "plain";
  if (several && mode != "seeds") {
    throw InvalidInput(setting("mode", mode) + " compares one test image; several are compared " +
                       "with " + setting("mode", "seeds"));
  }
  if (mode == "seeds" && !several) {
    throw InvalidInput(setting("mode", "seeds") +
                       " needs at least two test images (renders of the same job with other "
                       "seeds)");
  }
  if (mode == "noise" && !variances) {
    throw InvalidInput(setting("mode", "noise") +
                       " needs both images' variance channels (render with " +
                       setting("stats_channels") + " to an .exr)");
  }
  return mode;
}

}  // namespace

ImageComparison compare_images(const DiffInput& reference, const std::vector<DiffInput>& tests,
                               const ComparisonSettings& settings) {
  if (tests.empty()) throw InvalidInput("no test image to compare with the reference");
  for (const DiffInput& test : tests) check_comparable(test, reference);
  ImageComparison c;
  c.mode = chosen_mode(settings.mode, reference, tests);
  // Several renders are judged, and pictured, by their mean.
  c.test = tests.size() > 1 ? mean_image(tests) : tests[0];
  c.non_finite = find_non_finite(c.test, reference);
  if (c.mode == "plain") {
    const PlainDiff& d = c.plain.emplace(plain_diff(c.test, reference, settings.thresholds));
    c.verdict = d.verdict, c.description = describe(d, settings.thresholds);
  } else {
    const NoiseDiff& d = c.noise.emplace(
        c.mode == "seeds" ? seeds_diff(tests, reference, settings.block, settings.alpha)
                          : noise_diff(c.test, reference, settings.block, settings.alpha));
    c.verdict = d.verdict, c.description = describe(d);
  }
  if (c.non_finite.pixels > 0) c.verdict = DiffVerdict::Fail;
  return c;
}

ImageComparison compare_image_files(const std::string& reference,
                                    const std::vector<std::string>& tests,
                                    const ComparisonSettings& settings) {
  DiffInput ref = read_diff_input(reference);
  check_memory_for(tests.size() + 1, ref);
  std::vector<DiffInput> images;
  for (const std::string& path : tests) {
    images.push_back(read_diff_input(path));
    try {
      check_comparable(images.back(), ref);
    } catch (const ImagesNotComparable& e) {
      throw ImagesNotComparable("image " + quote_value(path) +
                                " against the reference: " + e.what());
    }
  }
  ImageComparison c = compare_images(ref, images, settings);
  c.reference = std::move(ref);
  return c;
}

}  // namespace rtiow
