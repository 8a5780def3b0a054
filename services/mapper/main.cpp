// relplane-mapper: the Relative Plane algorithm as a service. Subscribes PLANES (untransformed
// planes per iteration), publishes POSE for every plane set (same utime/seq) and MAP when the
// map changed, at most 10 times per simulated second and once more at shutdown. With
// --checkpoint it journals every plane set it processed and, started again, replays the journal
// first (journal.hpp), so a restarted mapper goes on with the map it had.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>

#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/common/service_start.hpp"
#include "service.hpp"

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"relplane-mapper: the Relative Plane algorithm (PLANES -> POSE, MAP)"};
  ServiceStart start;
  AddServiceFlags(parser, "mapper", &start);
  std::string checkpoint;
  parser.Add("--checkpoint", &checkpoint,
             "Journal of the processed plane sets: replayed on start when it exists, then "
             "appended to (the launcher gives RUN/mapper.journal)");
  if (const auto code = parser.Parse(argc, argv)) return *code;

  mapper::MapperOptions options;
  if (const auto code = LoadSectionOptions<mapper::MapperOptions>(
          start, "relplane-mapper", mapper::LoadMapperOptions, &options)) {
    return *code;
  }

  std::unique_ptr<bus::Bus> bus = OpenServiceBus(start);
  if (!bus) return 1;
  InstallStopHandlers();
  mapper::MapperService service(*bus, options);
  if (!checkpoint.empty() && !service.Resume(checkpoint)) return 1;
  service.Subscribe();
  spdlog::info("listening on PLANES");
  const int result = RunService(*bus, service.Stats());
  service.PublishMap();  // once more at shutdown
  return result;
}
