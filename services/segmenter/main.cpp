// relplane-segmenter: EM plane segmentation as a service. Subscribes SENSOR_POINTS, publishes
// one PLANES message per cloud (sensor frame, same utime/seq).

#include <spdlog/spdlog.h>

#include <iostream>

#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "service.hpp"

int main(int argc, char** argv) {
  using namespace relplane;
  CLI::App app{"relplane-segmenter: EM plane segmentation (SENSOR_POINTS -> PLANES)"};
  cli::CommonFlags flags;
  cli::AddCommonFlags(app, &flags);
  bool check_config = false;
  app.add_flag("--check-config", check_config,
               "Check the `segmenter` section of --config and exit");
  if (const auto code = cli::Parse(app, argc, argv)) return *code;

  segmenter::ServiceOptions options;
  try {
    cli::SetupLogging("relplane-segmenter", flags.log_level);
    options = segmenter::LoadServiceOptions(flags.config);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  if (check_config) return 0;

  std::unique_ptr<bus::Bus> bus;
  try {
    bus = bus::OpenLcmBus(bus::ResolveUrl(flags.lcm_url));
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  InstallStopHandlers();
  segmenter::SegmenterService service(*bus, options);
  service.Subscribe();
  spdlog::info("listening on SENSOR_POINTS");
  return RunService(*bus, service.Stats());
}
