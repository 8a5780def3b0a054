#include "relplane/common/service_start.hpp"

#include <spdlog/spdlog.h>

#include "relplane/common/receive_buffer.hpp"

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

namespace {

std::unique_ptr<bus::Bus> Open(const std::string& url) {
  try {
    return bus::OpenLcmBus(url);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return nullptr;
  }
}

}  // namespace

std::unique_ptr<bus::Bus> OpenServiceBus(const ServiceStart& start) {
  return Open(bus::ResolveUrl(start.flags.lcm_url));
}

std::optional<ServiceBuses> OpenServiceBuses(const ServiceStart& start) {
  const std::string main_url = bus::ResolveUrl(start.flags.lcm_url);
  const std::string cloud_url = bus::ResolveCloudUrl(start.cloud_url, main_url);
  const bool one_bus = cloud_url == main_url;
  ServiceBuses buses;
  buses.main = Open(one_bus ? bus::CloudBusUrl(main_url) : main_url);
  if (!buses.main) return std::nullopt;
  if (one_bus) return buses;
  buses.cloud = Open(bus::CloudBusUrl(cloud_url));
  if (!buses.cloud) return std::nullopt;
  return buses;
}

}  // namespace relplane
