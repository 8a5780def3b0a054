#pragma once
// Flags every relplane executable shares, and spdlog set up from --log-level.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace relplane::cli {

struct CommonFlags {
  std::string config;            // --config FILE: a scenario; the service reads its own section
  std::string lcm_url;           // --lcm-url URL: else $LCM_DEFAULT_URL, else LCM's default
  std::string log_level = "info";
};

// Adds --config, --lcm-url and --log-level to `app`.
void AddCommonFlags(CLI::App& app, CommonFlags* flags);

// Parses argv. Returns an exit code when the program should stop now (0 after --help,
// 2 after a usage error, printed as one line), std::nullopt to go on.
std::optional<int> Parse(CLI::App& app, int argc, char** argv);

// Sets the default spdlog logger to stderr with `name` in each line, at `level`
// (trace, debug, info, warn, error, critical, off). Throws std::invalid_argument otherwise.
void SetupLogging(const std::string& name, const std::string& level);

// Exit code for bad configuration or arguments (issue: "exit code 2, nothing started").
constexpr int kExitConfig = 2;

}  // namespace relplane::cli
