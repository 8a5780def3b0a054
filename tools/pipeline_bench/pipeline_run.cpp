#include "pipeline_run.hpp"

#include <poll.h>
#include <unistd.h>

#include <relplane/plane_set_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>
#include <thread>

#include "bus_url.hpp"
#include "child.hpp"
#include "process_cpu.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/service_runtime.hpp"

namespace relplane::bench {
namespace {

namespace fs = std::filesystem;

// The URLs of one run: the main bus and the cloud bus (the same with --one-bus), on free ports.
struct Urls {
  std::string main, clouds;
};

Urls PrivateUrls(bool one_bus) {
  const std::set<int> bound = [] {
    const auto ports = launch::BoundUdpPorts(launch::ReadProcNetUdp());
    return std::set<int>(ports.begin(), ports.end());
  }();
  const long buffer = std::min<long>(launch::ReceiveBufferMax(), 64L << 20);
  std::vector<std::string> urls;
  int taken = -1;
  for (int i = 0; i < (one_bus ? 1 : 2); ++i) {
    const uint64_t seed = static_cast<uint64_t>(getpid()) * 7919u +
                          static_cast<uint64_t>(MonotonicMicros()) + static_cast<uint64_t>(i);
    const auto port = launch::ChoosePort(seed, [&](int p) { return p == taken || bound.count(p) > 0; });
    if (!port) throw std::runtime_error("no free udp port for a private bus");
    taken = *port;
    urls.push_back(launch::MakeUdpmUrl(*port, buffer));
  }
  return {urls.front(), urls.back()};
}

// Machine-wide busy CPU and our processes' CPU at one moment, to tell the rest of the machine's
// work during a run.
struct CpuMark {
  double machine = -1.0;
  std::vector<double> ours;
  int64_t micros = 0;
};

// Cores' worth of CPU the other processes used between two marks; negative when unknown.
double OtherCores(const CpuMark& a, const CpuMark& b) {
  if (a.machine < 0.0 || b.machine < 0.0 || b.micros <= a.micros) return -1.0;
  double ours = 0.0;
  for (size_t k = 0; k < a.ours.size() && k < b.ours.size(); ++k) {
    if (a.ours[k] >= 0.0 && b.ours[k] >= 0.0) ours += b.ours[k] - a.ours[k];
  }
  return std::max(0.0, (b.machine - a.machine - ours) / ((b.micros - a.micros) / 1e6));
}

// Passes a child's output on (with --verbose) so its pipes never fill up.
void Drain(launch::Child& child, bool verbose) {
  for (int fd : {child.OutFd(), child.ErrFd()}) {
    if (fd < 0) continue;
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 0) <= 0) continue;
    for (const std::string& line : child.ReadLines(fd)) {
      if (verbose) std::cerr << "[" << child.Name() << "] " << line << "\n";
    }
  }
}

// One run: fresh services on a fresh bus, `clouds` published at `rate_hz` (0: unpaced).
// Stops the children: SIGINT, then up to two seconds each to end.
void StopChildren(std::vector<std::unique_ptr<launch::Child>>& children, bool verbose) {
  for (auto& c : children) c->SignalGroup(SIGINT);
  for (auto& c : children) {
    for (int i = 0; i < 100 && kill(c->Pid(), 0) == 0; ++i) {
      Drain(*c, verbose);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
}

}  // namespace


// The bus floor: `pings` round trips to relplane-bus-echo with messages of a cloud's size and
// of a pose's size, laid out on the buses as the pipeline's messages are (pings where the clouds
// go, replies where the poses come back), paced at 100 Hz so that, like the pipeline's frames,
// each waits for a sleeping process to wake.
BusFloor MeasureFloor(const Flags& flags, const std::string& bin_dir, size_t cloud_bytes) {
  const Urls urls = PrivateUrls(flags.one_bus);
  std::vector<std::unique_ptr<launch::Child>> children;
  children.push_back(std::make_unique<launch::Child>(launch::ChildSpec{
      "bus-echo", {bin_dir + "/relplane-bus-echo", "--lcm-url", urls.clouds, "--reply-url",
                   urls.main}}));
  auto replies = bus::OpenLcmBus(urls.main);
  std::unique_ptr<bus::Bus> own_pings;
  if (urls.clouds != urls.main) own_pings = bus::OpenLcmBus(urls.clouds);
  bus::Bus& pings = own_pings ? *own_pings : *replies;
  int64_t last_reply = -1;
  replies->SubscribeRaw(
      kFloorPong,
      [&](const std::string&, const uint8_t* data, size_t size) { last_reply = PingSeq(data, size); },
      bus::kDefaultQueueCapacity);
  // Round trip of ping `seq`, ms; negative after 200 ms without its reply.
  auto round_trip = [&](int64_t seq, size_t bytes) {
    const std::vector<uint8_t> ping = MakePing(seq, bytes);
    const int64_t t0 = MonotonicMicros();
    pings.PublishRaw(kFloorPing, ping.data(), ping.size());
    while (last_reply != seq && MonotonicMicros() - t0 < 200'000) replies->Handle(5);
    return last_reply == seq ? (MonotonicMicros() - t0) / 1000.0 : -1.0;
  };
  int64_t seq = 0;
  const int64_t ready_deadline = MonotonicMicros() + 5'000'000;
  while (round_trip(seq++, 8) < 0.0 && MonotonicMicros() < ready_deadline) {
    for (auto& c : children) Drain(*c, flags.verbose);
  }
  BusFloor floor;
  const size_t pose_bytes = static_cast<size_t>(pose_t{}.getEncodedSize());
  for (auto [bytes, summary] : {std::pair{cloud_bytes, &floor.cloud_round_trip},
                                std::pair{pose_bytes, &floor.pose_round_trip}}) {
    std::vector<double> ms;
    int64_t next = MonotonicMicros();
    for (int i = 0; i < flags.floor_pings && !StopRequested(); ++i) {
      next += 10'000;
      const double rtt = round_trip(seq++, bytes);
      if (rtt >= 0.0) ms.push_back(rtt);
      while (MonotonicMicros() < next) replies->Handle(1);
    }
    *summary = Summarise(ms);
  }
  StopChildren(children, flags.verbose);
  return floor;
}

RateResult RunAtRate(const Flags& flags, const std::string& bin_dir,
                     const std::vector<std::vector<uint8_t>>& clouds, double rate_hz,
                     std::vector<double>* e2e_ms) {
  const Urls urls = PrivateUrls(flags.one_bus);
  const std::string& url = urls.main;

  std::vector<std::unique_ptr<launch::Child>> children;
  for (const std::string name : {"segmenter", "mapper"}) {
    const std::string exe = bin_dir + "/relplane-" + name;
    if (!fs::exists(exe)) throw std::runtime_error(exe + " is not built");
    std::vector<std::string> argv = {exe, "--config", flags.scenario, "--lcm-url", url,
                                     "--log-level", "warn"};
    if (name == "segmenter" && urls.clouds != url) {
      argv.insert(argv.end(), {"--cloud-url", urls.clouds});
    }
    children.push_back(std::make_unique<launch::Child>(launch::ChildSpec{name, argv}));
  }

  // The bench reads the main bus only; it publishes the clouds on the cloud bus.
  auto bus = bus::OpenLcmBus(url);
  std::unique_ptr<bus::Bus> own_cloud_bus;
  if (urls.clouds != url) own_cloud_bus = bus::OpenLcmBus(urls.clouds);
  bus::Bus& cloud_bus = own_cloud_bus ? *own_cloud_bus : *bus;
  LatencyTable table;
  std::set<std::string> ready;
  auto ignore = [](const std::string&) {};
  bus::Subscribe<plane_set_t>(*bus, "PLANES", [&](const plane_set_t& m) {
    table.Stamp(Stage::kPlanes, m.seq, MonotonicMicros());
  }, ignore);
  bus::Subscribe<pose_t>(*bus, "POSE", [&](const pose_t& m) {
    table.Stamp(Stage::kPose, m.seq, MonotonicMicros());
  }, ignore);
  bus::Subscribe<status_t>(*bus, "STATUS", [&](const status_t& m) { ready.insert(m.service); },
                           ignore);

  // Services publish STATUS once a second from their loop: seeing both means both listen.
  const int64_t ready_deadline = MonotonicMicros() + 5'000'000;
  while (ready.size() < children.size() && MonotonicMicros() < ready_deadline) {
    bus->Handle(50);
    for (auto& c : children) Drain(*c, flags.verbose);
  }
  if (ready.size() < children.size()) std::cerr << "warning: services slow to report ready\n";

  // CPU used by each process over the run, read before the services are told to stop.
  std::vector<pid_t> pids = {getpid()};
  for (const auto& c : children) pids.push_back(c->Pid());
  auto cpu_now = [&] {
    CpuMark mark;
    mark.machine = MachineBusySeconds().value_or(-1.0);
    for (pid_t pid : pids) mark.ours.push_back(ProcessCpuSeconds(pid).value_or(-1.0));
    mark.micros = MonotonicMicros();
    return mark;
  };
  // Warm-up: the first frames, each sent once the one before came back as POSE (or after a
  // second), timed apart and not in the run's figures.
  const size_t warmup = std::min(clouds.size(), static_cast<size_t>(std::max(0, flags.warmup_frames)));
  std::vector<double> warmup_ms;
  for (size_t i = 0; i < warmup && !StopRequested(); ++i) {
    const int64_t sent = MonotonicMicros();
    table.Stamp(Stage::kPublished, static_cast<int64_t>(i), sent);
    cloud_bus.PublishRaw("SENSOR_POINTS", clouds[i].data(), clouds[i].size());
    while (MonotonicMicros() - sent < 1'000'000 && table.EndToEndMs().size() <= i) {
      bus->Handle(10);
      for (auto& c : children) Drain(*c, flags.verbose);
    }
  }
  warmup_ms = table.EndToEndMs();
  table.Forget();

  const CpuMark cpu_start = cpu_now();

  const int64_t start = MonotonicMicros();
  size_t published = 0;
  for (size_t i = warmup; i < clouds.size() && !StopRequested(); ++i) {
    if (rate_hz > 0.0) {
      const int64_t due = start + static_cast<int64_t>((i - warmup) * 1e6 / rate_hz);
      while (MonotonicMicros() < due) {
        bus->Handle(static_cast<int>(std::max<int64_t>(1, (due - MonotonicMicros()) / 1000)));
      }
    } else {
      while (bus->Handle(1) > 0) {
      }
    }
    table.Stamp(Stage::kPublished, static_cast<int64_t>(i), MonotonicMicros());
    cloud_bus.PublishRaw("SENSOR_POINTS", clouds[i].data(), clouds[i].size());
    ++published;
    for (auto& c : children) Drain(*c, flags.verbose);
  }
  const double publish_s = (MonotonicMicros() - start) / 1e6;
  // Let the pipeline drain: up to two seconds after the last POSE arrived.
  int64_t quiet_since = MonotonicMicros();
  size_t seen = 0;
  while (MonotonicMicros() - quiet_since < 2'000'000) {
    bus->Handle(20);
    const size_t now_seen = table.EndToEndMs().size();
    if (now_seen != seen) {
      seen = now_seen;
      quiet_since = MonotonicMicros();
    }
    if (seen == published) break;
  }
  const CpuMark cpu_end = cpu_now();
  auto cpu_ms_per_frame = [&](size_t k) {
    if (cpu_start.ours[k] < 0.0 || cpu_end.ours[k] < 0.0 || published == 0) return -1.0;
    return (cpu_end.ours[k] - cpu_start.ours[k]) * 1000.0 / static_cast<double>(published);
  };
  StopChildren(children, flags.verbose);
  *e2e_ms = table.EndToEndMs();
  RateResult result = table.Summarise(rate_hz, publish_s);
  result.warmup_ms = warmup_ms;
  result.bench_cpu_ms = cpu_ms_per_frame(0);
  result.segmenter_cpu_ms = cpu_ms_per_frame(1);  // children: segmenter, then mapper
  result.mapper_cpu_ms = cpu_ms_per_frame(2);
  result.other_cores = OtherCores(cpu_start, cpu_end);
  result.load_average = LoadAverage();
  return result;
}

}  // namespace relplane::bench
