#include "core/limits/nearest_name.h"

#include <algorithm>
#include <cstdint>

namespace rtiow {
namespace {

// Edit distance with a swap of neighbours counting one (optimal string alignment): "widht" is
// one edit from "width".
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

}  // namespace

std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = SIZE_MAX;
  bool best_continues = false;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    // At equal distance, a name the word begins ("of" of "off" rather than "on"): a word cut
    // short is the likelier slip.
    const bool continues = candidate.starts_with(word);
    if (distance < best_distance || (distance == best_distance && continues && !best_continues)) {
      best = candidate, best_distance = distance, best_continues = continues;
    }
  }
  const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  return best_distance <= allowed ? best : "";
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string meant = nearest_name(word, candidates);
  return meant.empty() ? "" : "; did you mean " + meant + "?";
}

}  // namespace rtiow
