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
  if (const auto code = parser.Parse(argc, argv)) return *code;

  segmenter::ServiceOptions options;
  if (const auto code = LoadSectionOptions<segmenter::ServiceOptions>(
          start, "relplane-segmenter", segmenter::LoadServiceOptions, &options)) {
    return *code;
  }

  std::unique_ptr<bus::Bus> bus = OpenServiceBus(start, Receives::kClouds);
  if (!bus) return 1;
  InstallStopHandlers();
  segmenter::SegmenterService service(*bus, options);
  service.Subscribe();
  spdlog::info("listening on SENSOR_POINTS ({})", bus->Url());
  return RunService(*bus, service.Stats());
}
