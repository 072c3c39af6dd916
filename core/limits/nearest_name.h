#pragma once
// The name a slip meant: "--widht" is one edit from "--width", "covr" from "cover". For the
// messages that refuse a name (an option, a command, a scene).

#include <string>
#include <string_view>
#include <vector>

namespace rtiow {

// The candidate nearest to `word` by edit distance (a swap of neighbours counts one), if it is
// near enough to be a likely slip (at most a third of the word, and at least 1, at most 3
// edits); empty otherwise.
std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates);

// "; did you mean <nearest>?" for a refusal's message, or empty when nothing is near enough.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace rtiow
