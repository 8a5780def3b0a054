// relplane-segmenter: EM plane segmentation as a service. Subscribes SENSOR_POINTS, publishes
// one PLANES message per cloud (sensor frame, same utime/seq).

#include <spdlog/spdlog.h>

#include <iostream>

#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/common/service_start.hpp"
#include "service.hpp"

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"relplane-segmenter: EM plane segmentation (SENSOR_POINTS -> PLANES)"};
  ServiceStart start;
  AddServiceFlags(parser, "segmenter", &start);
  AddCloudUrlFlag(parser, &start);
  if (const auto code = parser.Parse(argc, argv)) return *code;

  segmenter::ServiceOptions options;
  if (const auto code = LoadSectionOptions<segmenter::ServiceOptions>(
          start, "relplane-segmenter", segmenter::LoadServiceOptions, &options)) {
    return *code;
  }

  std::optional<ServiceBuses> buses = OpenServiceBuses(start);
  if (!buses) return 1;
  InstallStopHandlers();
  segmenter::SegmenterService service(buses->Cloud(), *buses->main, options);
  service.Subscribe();
  spdlog::info("listening on SENSOR_POINTS{}",
               buses->cloud ? " (cloud bus " + buses->cloud->Url() + ")" : std::string());
  // Only the cloud bus is read: the main bus, written to, never delivers its traffic here.
  return RunService(buses->Cloud(), *buses->main, service.Stats());
}
