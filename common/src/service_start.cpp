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

std::unique_ptr<bus::Bus> OpenServiceBus(const ServiceStart& start, Receives receives) {
  std::string url = bus::ResolveUrl(start.flags.lcm_url);
  if (receives == Receives::kClouds) url = bus::CloudBusUrl(url);
  try {
    return bus::OpenLcmBus(url);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return nullptr;
  }
}

}  // namespace relplane
