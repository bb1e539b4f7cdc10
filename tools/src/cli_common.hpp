// What only the program has: its exit codes and the declarations of the option groups that several subcommands
// share. What the options mean (the argument structs and what is made of them) lives in rockfit::app, below both
// the program and the Python module, so that both run the same code.
#pragma once

#include <CLI/CLI.hpp>

#include "rockfit/app/block_args.hpp"
#include "rockfit/app/fit_setup.hpp"
#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/app/json_values.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/app/recording_input.hpp"

namespace rockfit::tools {

// The subcommands are written in terms of the application layer.
using namespace rockfit::app;

// Exit codes of docs/design.md §9.
enum ExitCodes : int {
  kExitOk = 0,
  kExitUsage = 1,
  kExitBadInput = 2,
  kExitNumerical = 3,
  kExitCannotWrite = 4,
};

void AddBlockOptions(CLI::App& app, BlockArgs& args);
void AddFitOptions(CLI::App& app, FitArgs& args);
void AddMetricsOptions(CLI::App& app, MetricsArgs& args);
void AddRecordingOptions(CLI::App& app, RecordingArgs& args);
void AddGroundMotionOptions(CLI::App& app, GroundMotionArgs& args);

}  // namespace rockfit::tools
