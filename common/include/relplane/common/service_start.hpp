#pragma once
// The start every service shares (DESIGN.md): --config, --lcm-url, --log-level and
// --check-config; logging; its options from its section of the scenario; the bus.

#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"

namespace relplane {

struct ServiceStart {
  cli::CommonFlags flags;
  std::string cloud_url;  // --cloud-url, for the services that touch SENSOR_POINTS
  bool check_config = false;
};

// The buses of a service that touches clouds: SENSOR_POINTS on `Cloud()`, everything else on
// `main`. One bus when both URLs are the same.
struct ServiceBuses {
  std::unique_ptr<bus::Bus> main;
  std::unique_ptr<bus::Bus> cloud;  // null when the cloud URL is the main one
  bus::Bus& Cloud() { return cloud ? *cloud : *main; }
};

// Adds the common flags and --check-config (which checks section `section` of --config).
void AddServiceFlags(cli::Parser& parser, const std::string& section, ServiceStart* start);

// Adds --cloud-url (the bus of SENSOR_POINTS; default: the main bus).
void AddCloudUrlFlag(cli::Parser& parser, ServiceStart* start);

// Sets up logging as `name`, then `*options = load(config file)`. Returns the exit code when
// the program should stop: 2 after a bad option (its one line on stderr), 0 after
// --check-config; std::nullopt to go on.
template <class Options>
std::optional<int> LoadSectionOptions(const ServiceStart& start, const std::string& name,
                                      const std::function<Options(const std::string&)>& load,
                                      Options* options) {
  try {
    cli::SetupLogging(name, start.flags.log_level);
    *options = load(start.flags.config);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  if (start.check_config) return 0;
  return std::nullopt;
}

// The bus of --lcm-url, else $LCM_DEFAULT_URL, else LCM's default; nullptr (reason logged)
// when it cannot be opened.
std::unique_ptr<bus::Bus> OpenServiceBus(const ServiceStart& start);
// The main bus and, when --cloud-url names another, the cloud bus; std::nullopt (reason
// logged) when one cannot be opened. The bus that carries clouds asks for a receive buffer big
// enough for them (bus::CloudBusUrl).
std::optional<ServiceBuses> OpenServiceBuses(const ServiceStart& start);

}  // namespace relplane
