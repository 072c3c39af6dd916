#pragma once
// A request's setting as an error message names it, in the words of whoever asked. The
// library's own names are the render command's long options with underscores ("min_spp",
// "sample_range"), which the Python module will take as keyword arguments; a front end with
// other spellings says so once, at its start (the command line writes "--min-spp 2"). So the
// core never spells a front end's options, and each front end reads its own words back.

#include <string>
#include <string_view>

namespace rtiow {

// Writes `name` and, where not empty, its `value` as the front end spells them.
using SettingSpeller = std::string (*)(std::string_view name, std::string_view value);

// Call once before any render: renders in flight read the speller without a lock.
void spell_settings_as(SettingSpeller speller);

// `name` ("min_spp") and `value` ("2") as the front end spells them: "min_spp=2" by default,
// "--min-spp 2" on the command line.
std::string setting(std::string_view name, std::string_view value = {});

}  // namespace rtiow
