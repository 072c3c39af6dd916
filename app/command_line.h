#pragma once
// rtiow's command line, its grammar in one place (app/command_line.cpp, the one file that
// declares options): every command's options bound to plain structs, checked as they are read,
// --help and --version, and the refusals of what cannot be parsed. Each command's own file
// then runs it from its struct, with no parser in sight (as pbrt-v4's cmd/pbrt.cpp fills one
// options struct and hands it to the library).

#include <optional>
#include <string>

#include "app/diff_command.h"
#include "app/measure/accuracy_command.h"
#include "app/measure/bench_command.h"
#include "app/merge_command.h"
#include "app/render/render_command.h"
#include "app/scene_command.h"

namespace rtiow {

enum class Command { Render, Scene, Merge, Denoise, Bench, BenchPoint, Accuracy, Diff };

struct CommandLine {
  Command command = Command::Render;
  RenderCommand render;
  SceneOptions scene;
  MergeOptions merge;
  MergeOptions denoise;  // `rtiow denoise`: a merge that denoises
  BenchOptions bench;
  PointOptions point;
  AccuracyOptions accuracy;
  DiffOptions diff;
};

// Parses argv into `out`. Help, the version (`version_text`) and every refusal are printed
// here (by the first rank alone unless `speaks`); their exit code is returned. nullopt: `out`
// holds the command to run.
std::optional<int> parse_command_line(int argc, char** argv, const std::string& version_text,
                                      bool speaks, CommandLine& out);

}  // namespace rtiow
