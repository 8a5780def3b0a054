// relplane-bench: the whole pipeline (segmenter + mapper as real processes on a private bus)
// fed with simulated clouds at rising rates; latency per stage and end to end, matched by seq
// on this host's monotonic clock (issue "Benchmark"). Clouds are made before each run so the
// simulator's own cost is not in the figures.

#include <poll.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>

#include <chrono>
#include <csignal>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

#include "bus_floor.hpp"
#include "bus_url.hpp"
#include "child.hpp"
#include "convert.hpp"
#include "latency_table.hpp"
#include "options_yaml.hpp"
#include "process_cpu.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "report.hpp"
#include "stage_profile.hpp"

namespace fs = std::filesystem;
using namespace relplane;
using namespace relplane::bench;

namespace {

struct Flags {
  std::string scenario;
  std::string out;
  // 300: the rate the budget asks to hold, measured directly rather than between 240 and 480.
  std::vector<double> rates = {30, 60, 120, 240, 300, 480, 960, 0};
  std::vector<double> large_rates = {30, 60};
  int frames = 300;
  int large_frames = 90;
  int floor_pings = 200;
  // Frames sent to each fresh pipeline before the timed ones: its first clouds of a size pay for
  // the services' buffers and first-touch pages, which a service running for hours pays once.
  // They are timed apart (RateResult::warmup_ms), not dropped from the report.
  int warmup_frames = 2;
  bool skip_large = false;
  bool one_bus = false;
  bool verbose = false;
};

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

std::string MachineName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores";
}

// The clouds of the first `count` iterations of the scenario at `width` x `height`, encoded.
std::vector<std::vector<uint8_t>> MakeClouds(sim::SimOptions options, int width, int height,
                                             int count, int* points_per_frame) {
  options.sensor.width = width;
  options.sensor.height = height;
  sim::Simulation simulation(options);
  count = static_cast<int>(std::min<int64_t>(count, simulation.NumIterations()));
  std::vector<std::vector<uint8_t>> clouds;
  int64_t points = 0;
  for (int k = 0; k < count; ++k) {
    const point_cloud_t cloud = sim::ToPointCloud(simulation.Frame(k), k, simulation.Utime(k));
    points += cloud.num_points;
    std::vector<uint8_t> bytes(cloud.getEncodedSize());
    cloud.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    clouds.push_back(std::move(bytes));
  }
  *points_per_frame = count > 0 ? static_cast<int>(points / count) : 0;
  return clouds;
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

}  // namespace

int main(int argc, char** argv) {
  Flags flags;
  cli::Parser parser{
      "Pipeline latency and throughput against the 30 it/s budget: relplane-segmenter "
      "and relplane-mapper fed with simulated clouds at rising rates.",
      "relplane-bench"};
  parser.Add("scenario", &flags.scenario, "Scenario YAML (its sim section makes the clouds)")
      .ExistingFile()
      .Required();
  parser.Add("--out", &flags.out, "Folder for bench.json and latency.svg").Required();
  parser.Add("--rates", &flags.rates, "Sensor rates for 160x120 clouds, Hz; 0 = unpaced")
      .Delimiter(',')
      .ShowDefault();
  parser.Add("--large-rates", &flags.large_rates, "Sensor rates for 640x480 clouds, Hz")
      .Delimiter(',')
      .ShowDefault();
  parser.Add("--frames", &flags.frames, "Frames per 160x120 run").ShowDefault();
  parser.Add("--large-frames", &flags.large_frames, "Frames per 640x480 run").ShowDefault();
  parser.Add("--warmup-frames", &flags.warmup_frames,
             "Frames sent to each fresh pipeline before the timed ones, one at a time (their "
             "latencies are in bench.json as warmup_ms, not in the figures)")
      .NonNegative()
      .ShowDefault();
  parser.Add("--floor-pings", &flags.floor_pings,
             "Round trips per message size for the bus floor").Positive().ShowDefault();
  parser.AddFlag("--skip-large", &flags.skip_large, "Only 160x120 clouds");
  parser.AddFlag("--one-bus", &flags.one_bus,
                 "Clouds on the main bus, as before issue 54 (default: a bus of their own)");
  parser.AddFlag("--verbose", &flags.verbose, "Show the services' output");
  if (const auto code = parser.Parse(argc, argv)) return *code;
  InstallStopHandlers();

  sim::SimOptions sim_options;
  try {
    sim_options = sim::LoadServiceOptions(flags.scenario).sim;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  const std::string bin_dir = fs::canonical("/proc/self/exe").parent_path().string();

  BenchReport report;
  report.scenario = flags.scenario;
  report.machine = MachineName();
  report.buses = flags.one_bus ? "one bus for everything" : "clouds on a bus of their own";
  report.date = [] {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
    return std::string(text);
  }();
  struct Size {
    const char* name;
    int width, height, frames;
    std::vector<double> rates;
  };
  std::vector<Size> sizes = {{"160x120", 160, 120, flags.frames, flags.rates}};
  if (!flags.skip_large) sizes.push_back({"640x480", 640, 480, flags.large_frames, flags.large_rates});
  try {
    for (const Size& size : sizes) {
      ResolutionResult res;
      res.name = size.name;
      std::cerr << "making " << size.frames << " " << size.name << " clouds...\n";
      const auto clouds = MakeClouds(sim_options, size.width, size.height,
                                     size.frames + flags.warmup_frames, &res.points_per_frame);
      std::cerr << "timing the segmenter and mapper alone on them...\n";
      std::vector<std::vector<uint8_t>> plane_sets;
      res.segmenter_compute = Summarise(ProfileSegmenter(flags.scenario, clouds, &plane_sets));
      res.mapper_compute = Summarise(ProfileMapper(flags.scenario, plane_sets));
      std::cerr << "  segmenter alone p50 " << res.segmenter_compute.p50_ms << " ms, mapper alone p50 "
                << res.mapper_compute.p50_ms << " ms\n";
      std::cerr << "measuring the bus floor (" << flags.floor_pings
                << " round trips per message size)...\n";
      res.floor = MeasureFloor(flags, bin_dir, clouds.empty() ? 0 : clouds.front().size());
      std::cerr << "  bus floor " << res.floor.PipelineFloorMs() << " ms (round trips p50: cloud "
                << res.floor.cloud_round_trip.p50_ms << ", pose "
                << res.floor.pose_round_trip.p50_ms << " ms)\n";
      for (double rate : size.rates) {
        if (StopRequested()) break;
        std::vector<double> e2e;
        res.rates.push_back(RunAtRate(flags, bin_dir, clouds, rate, &e2e));
        std::cerr << "  " << ProgressLine(size.name, res.rates.back(), res.floor) << "\n";
        if (rate == 30.0) res.e2e_ms_at_30hz = e2e;
      }
      report.resolutions.push_back(std::move(res));
    }
  } catch (const std::exception& e) {
    std::cerr << "relplane-bench: " << e.what() << "\n";
    return 1;
  }

  const Verdict verdict = Judge(report);
  fs::create_directories(flags.out);
  std::ofstream(flags.out + "/bench.json") << [&] {
    std::ostringstream s;
    WriteJson(report, verdict, s);
    return s.str();
  }();
  std::ofstream svg(flags.out + "/latency.svg");
  WriteHistogramSvg(report, svg);
  PrintTable(report, verdict, std::cout);
  std::cout << "wrote " << flags.out << "/bench.json and " << flags.out << "/latency.svg\n";
  return verdict.pass ? 0 : 3;
}
