#include "relplane/common/cli.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <stdexcept>

namespace relplane::cli {
namespace {

// A number check whose message reads well (CLI11's own range checks print the largest double
// as the upper bound).
CLI::Validator NumberCheck(const std::function<bool(double)>& ok, const std::string& what) {
  return CLI::Validator(
      [ok, what](std::string& text) {
        try {
          size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && ok(value)) return std::string();
        } catch (const std::exception&) {
        }
        return "'" + text + "' must be " + what;
      },
      "NUMBER");
}

}  // namespace

Option& Option::Required() {
  option_->required();
  return *this;
}

Option& Option::ExistingFile() {
  option_->check(CLI::ExistingFile);
  return *this;
}

Option& Option::NonNegative() {
  option_->check(NumberCheck([](double v) { return v >= 0.0; }, "a number >= 0"));
  return *this;
}

Option& Option::Positive() {
  option_->check(NumberCheck([](double v) { return v > 0.0; }, "a number > 0"));
  return *this;
}

Option& Option::Range(double lo, double hi) {
  option_->check(CLI::Range(lo, hi));
  return *this;
}

Option& Option::ShowDefault() {
  option_->capture_default_str();
  return *this;
}

Option& Option::Delimiter(char c) {
  option_->delimiter(c);
  return *this;
}

Option& Option::OneValuePerUse() {
  option_->allow_extra_args(false)->take_all();
  return *this;
}

Parser::Parser(const std::string& description, const std::string& program)
    : app_(std::make_unique<CLI::App>(description, program)) {}

Parser::~Parser() = default;

Option Parser::Add(const std::string& name, std::string* value, const std::string& help) {
  return Option(app_->add_option(name, *value, help));
}

Option Parser::Add(const std::string& name, std::vector<std::string>* values,
                   const std::string& help) {
  return Option(app_->add_option(name, *values, help));
}

Option Parser::Add(const std::string& name, double* value, const std::string& help) {
  return Option(app_->add_option(name, *value, help));
}

Option Parser::Add(const std::string& name, std::vector<double>* values, const std::string& help) {
  return Option(app_->add_option(name, *values, help));
}

Option Parser::Add(const std::string& name, int* value, const std::string& help) {
  return Option(app_->add_option(name, *value, help));
}

Option Parser::Add(const std::string& name, int64_t* value, const std::string& help) {
  return Option(app_->add_option(name, *value, help));
}

void Parser::AddFlag(const std::string& name, bool* value, const std::string& help) {
  app_->add_flag(name, *value, help);
}

std::optional<int> Parser::Parse(int argc, char** argv) {
  try {
    app_->parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app_->help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app_->help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << app_->get_name() << ": " << e.what() << " (see --help)\n";
    return kExitConfig;
  }
  return std::nullopt;
}

void AddCommonFlags(Parser& parser, CommonFlags* flags) {
  parser
      .Add("--config", &flags->config,
           "Scenario YAML file; this program reads its own section of it")
      .ExistingFile();
  parser.Add("--lcm-url", &flags->lcm_url,
             "LCM bus URL (default: $LCM_DEFAULT_URL, then LCM's default)");
  parser.Add("--log-level", &flags->log_level, "trace, debug, info, warn, error, critical or off")
      .ShowDefault();
}

void SetupLogging(const std::string& name, const std::string& level) {
  const spdlog::level::level_enum parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") {
    throw std::invalid_argument("unknown log level '" + level + "'");
  }
  auto logger = spdlog::stderr_color_mt(name);
  logger->set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
  logger->set_level(parsed);
  spdlog::set_default_logger(logger);
}

}  // namespace relplane::cli
