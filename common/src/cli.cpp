#include "relplane/common/cli.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <stdexcept>

namespace relplane::cli {

void AddCommonFlags(CLI::App& app, CommonFlags* flags) {
  app.add_option("--config", flags->config,
                 "Scenario YAML file; this program reads its own section of it")
      ->check(CLI::ExistingFile);
  app.add_option("--lcm-url", flags->lcm_url,
                 "LCM bus URL (default: $LCM_DEFAULT_URL, then LCM's default)");
  app.add_option("--log-level", flags->log_level,
                 "trace, debug, info, warn, error, critical or off")
      ->capture_default_str();
}

std::optional<int> Parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << app.get_name() << ": " << e.what() << " (see --help)\n";
    return kExitConfig;
  }
  return std::nullopt;
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
