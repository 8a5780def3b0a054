#pragma once
// Command-line parsing for every relplane executable, the flags they all share, and spdlog set
// up from --log-level.
//
// CLI11 stays behind this header: it is header-only and compiles its parser and validators into
// every source that includes it (about 9 s each), so only cli.cpp includes it.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relplane::cli {

// Constraints on one option, chained: parser.Add("--rate", &rate, "...").NonNegative();
class Option {
 public:
  Option& Required();
  Option& ExistingFile();
  Option& NonNegative();  // a number >= 0
  Option& Positive();     // a number > 0
  Option& Range(double lo, double hi);
  Option& ShowDefault();      // the value before parsing appears in --help
  Option& Delimiter(char c);  // a list option also splits each value at c
  // One value per use and repeatable, so a positional argument may follow it.
  Option& OneValuePerUse();

 private:
  friend class Parser;
  explicit Option(CLI::Option* option) : option_(option) {}
  CLI::Option* option_;
};

// A program's flags and positional arguments. Names starting with "-" are flags, others are
// positional, in the order added.
class Parser {
 public:
  explicit Parser(const std::string& description, const std::string& program = "");
  ~Parser();
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;

  Option Add(const std::string& name, std::string* value, const std::string& help);
  Option Add(const std::string& name, std::vector<std::string>* values, const std::string& help);
  Option Add(const std::string& name, double* value, const std::string& help);
  Option Add(const std::string& name, std::vector<double>* values, const std::string& help);
  Option Add(const std::string& name, int* value, const std::string& help);
  Option Add(const std::string& name, int64_t* value, const std::string& help);
  void AddFlag(const std::string& name, bool* value, const std::string& help);

  // Parses argv. Returns an exit code when the program should stop now (0 after --help,
  // 2 after a usage error, printed as one line), std::nullopt to go on.
  std::optional<int> Parse(int argc, char** argv);

 private:
  std::unique_ptr<CLI::App> app_;
};

struct CommonFlags {
  std::string config;            // --config FILE: a scenario; the service reads its own section
  std::string lcm_url;           // --lcm-url URL: else $LCM_DEFAULT_URL, else LCM's default
  std::string log_level = "info";
};

// Adds --config, --lcm-url and --log-level to `parser`.
void AddCommonFlags(Parser& parser, CommonFlags* flags);

// Sets the default spdlog logger to stderr with `name` in each line, at `level`
// (trace, debug, info, warn, error, critical, off). Throws std::invalid_argument otherwise.
void SetupLogging(const std::string& name, const std::string& level);

// Exit code for bad configuration or arguments (issue: "exit code 2, nothing started").
constexpr int kExitConfig = 2;

}  // namespace relplane::cli
