// relplane-launch: runs one scenario as a set of processes on a bus private to the run, with
// the real lcm-logger recording it into the run folder (README "relplane-launch").
// Every check happens before the first process starts: a bad scenario starts nothing.

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "bus_url.hpp"
#include "log_merge.hpp"
#include "overrides.hpp"
#include "plan.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/options.hpp"
#include "scenario.hpp"
#include "setup.hpp"
#include "supervisor.hpp"
#include "verdict.hpp"

namespace relplane::launch {
namespace {

// The scenario as the services will get it.
struct Resolved {
  std::string text;       // RUN/scenario.yaml
  YAML::Node doc;         // the same, parsed
  LaunchOptions options;  // its `launch` section
  std::string name;       // names the run folder
};

// What runs: the services found, the source that ends the run, the tools.
struct Cast {
  std::vector<std::string> services;  // in the scenario's order, without the source
  std::vector<ServiceProgram> checkers;
  std::string source;
  std::string bin_dir, lcm_logger, lcm_logplayer;
};

// Where bare scenario names (`office`) are looked up.
const std::string kScenariosDir = std::string(RELPLANE_SOURCE_DIR) + "/scenarios";

// With --replay the scenario defaults to the one the recorded run got, beside its log.
void ResolveReplayDefaults(Request* request) {
  if (request->replay.empty()) return;
  if (!std::ifstream(request->replay)) throw SetupError(request->replay + ": cannot open the file");
  if (request->iterations >= 0) throw SetupError("--iterations does not apply to --replay");
  if (request->scenario.empty()) {
    const size_t slash = request->replay.find_last_of('/');
    request->scenario =
        (slash == std::string::npos ? std::string(".") : request->replay.substr(0, slash)) +
        "/scenario.yaml";
  }
}

// Top level and `launch` checked on the file as written (so lines point into it), then the
// --set overrides applied and `launch` read from the result.
Resolved ResolveScenario(Request& request) {
  if (request.scenario.empty()) throw SetupError("a SCENARIO file is required (see --help)");
  request.scenario = ResolveScenarioFile(request.scenario, kScenariosDir);
  const YAML::Node original = LoadScenario(request.scenario);
  const std::string original_text = ReadFile(request.scenario);
  ReadLaunchOptions(original_text, request.scenario);

  Resolved r;
  r.doc = YAML::Clone(original);
  for (const std::string& argument : request.sets) ApplyOverride(r.doc, ParseOverride(argument));
  // Without overrides the services get the file verbatim, comments included.
  r.text = request.sets.empty() ? original_text : ToYaml(r.doc);
  r.options = ReadLaunchOptions(r.text, request.scenario + " (with --set)");
  r.name = ScenarioName(r.doc, request.scenario) + (request.replay.empty() ? "" : "-replay");
  return r;
}

Cast FindCast(const Request& request, const Resolved& scenario) {
  const bool replay = !request.replay.empty();
  Cast cast;
  cast.source = replay ? kReplaySource : kSourceService;
  cast.bin_dir = request.bin_dir.empty() ? OwnDirectory() : request.bin_dir;
  for (const std::string& service : replay ? kReplayServices : scenario.options.services) {
    const std::string exe = cast.bin_dir + "/relplane-" + service;
    if (IsExecutable(exe)) {
      cast.services.push_back(service);
      cast.checkers.emplace_back(service, exe);
    } else if (request.allow_missing) {
      Say("warning: relplane-" + service + " is not built yet: running without it");
    } else {
      throw SetupError(exe + ": no such program (not built yet?); --allow-missing runs without it");
    }
  }
  // A section of a service that does not run is still checked, when the service is built.
  for (const char* section : {"sim", "segmenter", "mapper", "logger"}) {
    const std::string exe = cast.bin_dir + "/relplane-" + section;
    const bool listed =
        std::find(cast.services.begin(), cast.services.end(), section) != cast.services.end();
    if (!listed && scenario.doc[section] && IsExecutable(exe))
      cast.checkers.emplace_back(section, exe);
  }
  cast.lcm_logger = FindInPath("lcm-logger");
  if (cast.lcm_logger.empty())
    throw SetupError("lcm-logger not found in PATH (Debian: liblcm-bin)");
  if (replay) {
    cast.lcm_logplayer = FindInPath("lcm-logplayer");
    if (cast.lcm_logplayer.empty()) {
      throw SetupError("lcm-logplayer not found in PATH (Debian: liblcm-bin)");
    }
  }
  return cast;
}

// `text` with each `path`, and the :LINE:COLUMN numbers after it, replaced by `by`. (Hand-written
// rather than std::regex, which costs about 5 s of -O3 to compile.)
std::string ReplacePath(const std::string& text, const std::string& path, const std::string& by) {
  std::string out;
  size_t from = 0;
  for (size_t at = text.find(path); at != std::string::npos; at = text.find(path, from)) {
    out.append(text, from, at - from).append(by);
    from = at + path.size();
    while (from + 1 < text.size() && text[from] == ':' && text[from + 1] >= '0' &&
           text[from + 1] <= '9') {
      from = std::min(text.find_first_not_of("0123456789", from + 1), text.size());
    }
  }
  return out.append(text, from, std::string::npos);
}

// Each service checks its section: the file as written, then (if changed) the resolved text.
void CheckWithServices(const Request& request, const Resolved& scenario, const Cast& cast) {
  CheckConfig(cast.checkers, request.scenario, "");
  if (request.sets.empty()) return;
  char temp[] = "/tmp/relplane-scenario-XXXXXX";
  const int fd = mkstemp(temp);
  if (fd < 0) throw SetupError("cannot create a temporary file in /tmp");
  close(fd);
  try {
    WriteFile(temp, scenario.text);
    CheckConfig(cast.checkers, temp, "");
  } catch (const SetupError& e) {
    unlink(temp);
    // The services name the temporary file: name the scenario, whose key their message names.
    throw SetupError(
        ReplacePath(e.what(), temp, request.scenario + " (after the --set overrides)"));
  } catch (...) {
    unlink(temp);
    throw;
  }
  unlink(temp);
}

// The run's main bus and its cloud bus (SENSOR_POINTS alone; may be the main bus).
struct Buses {
  std::string url, cloud_url;
};

Buses ChooseBuses(const Request& request) {
  Buses buses;
  buses.url = ChooseUrl(request);
  buses.cloud_url = ChooseCloudUrl(request, buses.url);
  for (const std::string& url : {buses.url, buses.cloud_url}) {
    if (url.rfind("udpm://", 0) == 0 && !HasMulticastRoute()) {
      throw SetupError(
          "no multicast route for the udpm bus: as root, ip route add 224.0.0.0/4 dev lo");
    }
  }
  return buses;
}

// The udpm ports of the run's buses, to see the subscribers bind; empty when a bus has none
// (the supervisor then waits a moment instead).
std::vector<int> BusPorts(const Buses& buses) {
  std::vector<int> ports;
  for (const std::string& bus : {buses.url, buses.cloud_url}) {
    const std::optional<int> port = PortOfUrl(bus);
    if (!port) return {};
    if (ports.empty() || ports[0] != *port) ports.push_back(*port);
  }
  return ports;
}

// One bus.lcmlog holding every channel: the cloud recorder's log merged into it.
void MergeCloudLog(const std::string& run_dir) {
  const std::string log = run_dir + "/bus.lcmlog", clouds = run_dir + "/" + kCloudLog;
  const std::string merged = log + ".merging";
  std::string reason;
  if (!MergeLogs(log, clouds, merged, &reason) || std::rename(merged.c_str(), log.c_str()) != 0) {
    std::remove(merged.c_str());
    Say("warning: could not merge " + kCloudLog + " into bus.lcmlog (" + reason +
        "): the clouds stay in " + clouds);
    return;
  }
  std::remove(clouds.c_str());
}

std::string MakeRunFolder(const Request& request, const Resolved& scenario) {
  const std::string run_dir = ChooseRunDir(request, scenario.name);
  MakeDirectories(run_dir);
  if (!request.replay.empty() && SameFile(run_dir + "/bus.lcmlog", request.replay)) {
    throw SetupError(run_dir + ": the replay would record over the log it plays; choose --out");
  }
  WriteFile(run_dir + "/scenario.yaml", scenario.text);
  // A journal left by an earlier run in the same folder must not be resumed by this one.
  std::remove((run_dir + "/" + kMapperJournal).c_str());
  return run_dir;
}

// The run's last line: its verdict. A run that completed exits 0 only when every expectation
// held; a run without relplane-logger has no metrics and so no verdict.
int Conclude(const Cast& cast, const std::string& run_dir, int code) {
  if (code != kExitOk) {
    Say(std::string(code == kExitInterrupted ? "interrupted" : "FAILED") + ": run folder " +
        run_dir);
    return code;
  }
  if (std::find(cast.services.begin(), cast.services.end(), "logger") == cast.services.end()) {
    Say("done (no relplane-logger in the run: no verdict): run folder " + run_dir);
    return kExitOk;
  }
  std::string metrics;
  try {
    metrics = ReadFile(run_dir + "/metrics.json");
  } catch (const SetupError&) {
  }
  const Verdict verdict = VerdictOfMetrics(metrics);
  Say(verdict.line + "; run folder " + run_dir);
  switch (verdict.kind) {
    case Verdict::Kind::kPass:
    case Verdict::Kind::kNoExpectations:
      return kExitOk;
    case Verdict::Kind::kFail:
      return kExitExpectationFailed;
    case Verdict::Kind::kUnreadable:
      break;
  }
  return kExitFailed;
}

// lcm-spy on the run's bus, as one line to paste into another terminal.
std::string SpyCommand(const std::string& url) {
  return "java -cp " RELPLANE_SPY_CLASSPATH " lcm.spy.Spy --lcm-url='" + url + "'";
}

int Run(const Request& request, const Resolved& scenario, const Cast& cast, const Buses& buses,
        const std::string& run_dir) {
  const std::string& url = buses.url;
  setenv("LCM_DEFAULT_URL", url.c_str(), 1);  // for the children and anything they start
  std::vector<ChildSpec> children;
  for (const std::string& service : StartOrder(cast.services, cast.source)) {
    children.push_back(WithCloudUrl(ServiceCommand(service, cast.bin_dir,
                                                   run_dir + "/scenario.yaml", url, run_dir,
                                                   scenario.options, request.iterations),
                                    url, buses.cloud_url));
  }
  std::string listed;
  for (const std::string& service : cast.services) listed += (listed.empty() ? "" : ", ") + service;
  SupervisorOptions supervision;
  if (!request.replay.empty()) {
    for (ChildSpec& player : ReplayCommands(cast.lcm_logplayer, url, buses.cloud_url,
                                            request.replay, request.speed)) {
      if (player.name != cast.source) supervision.side_sources.push_back(player.name);
      children.push_back(std::move(player));
    }
    listed += (listed.empty() ? "" : ", ") + cast.source;
  }
  const bool record = scenario.options.record != kRecordNothing;
  const bool split = buses.cloud_url != url;
  Say("scenario " + scenario.name + ": " + (listed.empty() ? "no services" : listed) +
      (record ? " + lcm-logger (records " + scenario.options.record + ")" : ", nothing recorded"));
  Say("bus " + url);
  Say("spy: " + SpyCommand(url));
  if (split) Say("clouds (SENSOR_POINTS) on " + buses.cloud_url);
  Say("run folder " + run_dir);

  supervision.grace_s = scenario.options.grace_s;
  supervision.drain_s = scenario.options.drain_s;
  supervision.bus_ports = BusPorts(buses);
  supervision.source = cast.source;
  supervision.restart = scenario.options.restart;
  const int code = Supervise(RecorderCommands(cast.lcm_logger, url, buses.cloud_url, run_dir,
                                              scenario.options.record),
                             children, supervision);
  if (split && scenario.options.record == kRecordAll) MergeCloudLog(run_dir);
  return Conclude(cast, run_dir, code);
}

int Launch(Request request) {
  ResolveReplayDefaults(&request);
  const Resolved scenario = ResolveScenario(request);
  const Cast cast = FindCast(request, scenario);
  CheckWithServices(request, scenario, cast);
  const Buses buses = ChooseBuses(request);
  if (request.check) {
    Say(request.scenario + ": OK");
    return kExitOk;
  }
  const std::string run_dir = MakeRunFolder(request, scenario);
  return Run(request, scenario, cast, buses, run_dir);
}

}  // namespace
}  // namespace relplane::launch

int main(int argc, char** argv) {
  using relplane::launch::Request;
  relplane::cli::Parser parser{
      "Runs a scenario: its services on a private LCM bus, recorded by lcm-logger.",
      "relplane-launch"};
  Request request;
  parser.Add("scenario", &request.scenario,
             "Scenario YAML file (with --replay: default the log's RUN/scenario.yaml)");
  parser.Add("--out", &request.out,
             "Run folder (default: runs/NAME-UTCTIME, or under $RELPLANE_RUNS_DIR)");
  parser
      .Add("--set", &request.sets,
           "Override a scenario value: key.path=value (YAML value; lists as key[N]); "
           "repeatable")
      .OneValuePerUse();  // so the SCENARIO may follow it
  parser.Add("--lcm-url", &request.lcm_url, "Bus URL (default: a udpm port unique to the run)");
  parser.Add("--cloud-url", &request.cloud_url,
             "Bus URL of SENSOR_POINTS alone, joined only by the processes that use clouds "
             "(default: a second udpm port unique to the run; with --lcm-url: that bus)");
  parser.Add("--replay", &request.replay,
             "Feed this recorded bus.lcmlog's SENSOR_POINTS, SIM_TRUTH and SIM_WORLD to "
             "fresh segmenter, mapper and logger with lcm-logplayer, instead of the simulator");
  parser.Add("--speed", &request.speed, "Replay speed factor (1: as recorded)").Positive();
  parser
      .Add("--iterations", &request.iterations,
           "Stop the simulator after N iterations (passed to relplane-sim)")
      .NonNegative();
  parser.AddFlag("--check", &request.check,
                 "Validate the scenario with every service, start nothing");
  parser.AddFlag("--allow-missing", &request.allow_missing,
                 "Run without services that are not built yet (with a warning)");
  parser.Add("--bin-dir", &request.bin_dir,
             "Where relplane-<service> programs are (default: beside relplane-launch)");
  if (const auto code = parser.Parse(argc, argv)) return *code;
  try {
    return relplane::launch::Launch(request);
  } catch (const relplane::config::ConfigError& e) {
    std::cerr << e.what() << "\n";
  } catch (const relplane::launch::SetupError& e) {
    std::cerr << e.what() << "\n";
  } catch (const YAML::Exception& e) {
    std::cerr << request.scenario << ": " << e.what() << "\n";
  }
  return relplane::cli::kExitConfig;
}
