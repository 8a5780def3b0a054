// relplane-bus-echo: the far end of the benchmark's bus floor. Answers every FLOOR_PING read on
// --lcm-url with a FLOOR_PONG on --reply-url holding the ping's first kFloorReplyBytes bytes (its
// sequence number first), so a round trip is one message of the ping's size out and one of a
// pose's size back: the transport alone, between two processes, on the pipeline's kind of bus.

#include <algorithm>
#include <iostream>

#include "bus_floor.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"relplane-bus-echo: answers FLOOR_PING with FLOOR_PONG (relplane-bench's "
                     "bus floor)",
                     "relplane-bus-echo"};
  std::string url, reply_url;
  parser.Add("--lcm-url", &url, "Bus of the pings").Required();
  parser.Add("--reply-url", &reply_url, "Bus of the replies (default: the pings' bus)");
  if (const auto code = parser.Parse(argc, argv)) return *code;
  std::unique_ptr<bus::Bus> pings, replies;
  try {
    pings = bus::OpenLcmBus(url);
    if (!reply_url.empty() && reply_url != url) replies = bus::OpenLcmBus(reply_url);
  } catch (const std::exception& e) {
    std::cerr << "relplane-bus-echo: " << e.what() << "\n";
    return 1;
  }
  bus::Bus& out = replies ? *replies : *pings;
  pings->SubscribeRaw(
      bench::kFloorPing,
      [&out](const std::string&, const uint8_t* data, size_t size) {
        out.PublishRaw(bench::kFloorPong, data, std::min(size, bench::kFloorReplyBytes));
      },
      bus::kDefaultQueueCapacity);
  InstallStopHandlers();
  while (!StopRequested()) {
    if (pings->Handle(100) < 0 && !StopRequested()) return 1;
  }
  return 0;
}
