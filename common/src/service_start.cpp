#include "relplane/common/service_start.hpp"

#include <spdlog/spdlog.h>

namespace relplane {

void AddServiceFlags(cli::Parser& parser, const std::string& section, ServiceStart* start) {
  cli::AddCommonFlags(parser, &start->flags);
  parser.AddFlag(
      "--check-config", &start->check_config,
      "Check the `" + section + "` section of --config and exit (0, or 2 with the error)");
}

void AddCloudUrlFlag(cli::Parser& parser, ServiceStart* start) {
  parser.Add("--cloud-url", &start->cloud_url,
             "LCM bus URL of SENSOR_POINTS (default: the main bus); the launcher gives clouds "
             "a port of their own so that only the processes using them read them");
}

std::unique_ptr<bus::Bus> OpenServiceBus(const ServiceStart& start) {
  try {
    return bus::OpenLcmBus(bus::ResolveUrl(start.flags.lcm_url));
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return nullptr;
  }
}

std::optional<ServiceBuses> OpenServiceBuses(const ServiceStart& start) {
  ServiceBuses buses;
  buses.main = OpenServiceBus(start);
  if (!buses.main) return std::nullopt;
  const std::string cloud_url = bus::ResolveCloudUrl(start.cloud_url, buses.main->Url());
  if (cloud_url == buses.main->Url()) return buses;
  try {
    buses.cloud = bus::OpenLcmBus(cloud_url);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return std::nullopt;
  }
  return buses;
}

}  // namespace relplane
