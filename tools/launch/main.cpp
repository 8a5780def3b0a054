// relplane-launch: runs one scenario as a set of processes on a bus private to the run, with
// the real lcm-logger recording it into the run folder (README "relplane-launch").

#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bus_url.hpp"
#include "child.hpp"
#include "overrides.hpp"
#include "plan.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/options.hpp"
#include "scenario.hpp"
#include "supervisor.hpp"

namespace launch = relplane::launch;

namespace {

struct Flags {
  std::string scenario;
  std::string out;
  std::vector<std::string> sets;
  std::string lcm_url;
  std::string bin_dir;
  std::string replay;  // a recorded bus.lcmlog to feed to fresh services
  double speed = 1.0;
  long iterations = -1;
  bool check = false;
  bool allow_missing = false;
};

// Thrown for every "stop before anything started" problem; exit code 2.
struct SetupError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SetupError(path + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw SetupError(path + ": cannot write the file");
}

bool IsExecutable(const std::string& path) { return access(path.c_str(), X_OK) == 0; }

std::string OwnDirectory() {
  char buffer[4096];
  const ssize_t n = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) return ".";
  std::string path(buffer, static_cast<size_t>(n));
  return path.substr(0, path.find_last_of('/'));
}

bool SameFile(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

std::string FindInPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && IsExecutable(dir + "/" + program)) return dir + "/" + program;
  }
  return "";
}

void MakeDirectories(const std::string& path) {
  for (size_t slash = path.find('/', 1);; slash = path.find('/', slash + 1)) {
    const std::string prefix = path.substr(0, slash);
    if (mkdir(prefix.c_str(), 0755) != 0 && errno != EEXIST) {
      throw SetupError(prefix + ": cannot create the folder: " + std::strerror(errno));
    }
    if (slash == std::string::npos) return;
  }
}

std::string ChooseRunDir(const Flags& flags, const std::string& name) {
  if (!flags.out.empty()) return flags.out;
  const char* root = std::getenv("RELPLANE_RUNS_DIR");
  const std::string base =
      launch::DefaultRunDir(root && *root ? root : "runs", name, std::time(nullptr));
  std::string dir = base;
  struct stat info {};
  for (int i = 2; stat(dir.c_str(), &info) == 0; ++i) dir = base + "-" + std::to_string(i);
  return dir;
}

std::string ChooseUrl(const Flags& flags) {
  if (!flags.lcm_url.empty()) return flags.lcm_url;
  const std::vector<int> bound = launch::BoundUdpPorts(launch::ReadProcNetUdp());
  const uint64_t seed =
      (static_cast<uint64_t>(getpid()) << 32) ^
      static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  const std::optional<int> port = launch::ChoosePort(
      seed, [&](int p) { return std::find(bound.begin(), bound.end(), p) != bound.end(); });
  if (!port) throw SetupError("no free UDP port for the run's bus");
  constexpr long kWantedReceiveBuffer = 16l << 20;  // a second of 640x480 clouds is larger still
  const long rmem_max = launch::ReceiveBufferMax();
  return launch::MakeUdpmUrl(*port, rmem_max > 0 ? std::min(rmem_max, kWantedReceiveBuffer) : 0);
}

// Runs `relplane-NAME --config FILE --check-config` for each service; the first refusal ends
// the launch with the service's own one-line message.
void CheckConfig(const std::vector<std::pair<std::string, std::string>>& services,
                 const std::string& file, const std::string& note) {
  for (const auto& [name, exe] : services) {
    std::string output;
    int status = 0;
    try {
      status = launch::RunToEnd({exe, "--config", file, "--check-config"}, 20.0, &output);
    } catch (const std::exception& e) {
      throw SetupError(e.what());
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;
    while (!output.empty() && output.back() == '\n') output.pop_back();
    if (output.empty())
      output = "relplane-" + name + " --check-config " + launch::DescribeExit(status);
    throw SetupError(output + note);
  }
}

int Launch(Flags flags) {
  const bool replay = !flags.replay.empty();
  if (replay) {
    if (!std::ifstream(flags.replay)) throw SetupError(flags.replay + ": cannot open the file");
    if (flags.iterations >= 0) throw SetupError("--iterations does not apply to --replay");
    // By default the scenario the recorded run got, from its run folder.
    if (flags.scenario.empty()) {
      const size_t slash = flags.replay.find_last_of('/');
      flags.scenario =
          (slash == std::string::npos ? std::string(".") : flags.replay.substr(0, slash)) +
          "/scenario.yaml";
    }
  }
  if (flags.scenario.empty()) throw SetupError("a SCENARIO file is required (see --help)");
  const YAML::Node original = launch::LoadScenario(flags.scenario);
  const std::string original_text = ReadFile(flags.scenario);
  launch::ReadLaunchOptions(original_text, flags.scenario);

  YAML::Node resolved = YAML::Clone(original);
  for (const std::string& argument : flags.sets) {
    launch::ApplyOverride(resolved, launch::ParseOverride(argument));
  }
  // Without overrides the services get the file verbatim, comments included.
  const std::string resolved_text = flags.sets.empty() ? original_text : launch::ToYaml(resolved);
  const launch::LaunchOptions options =
      launch::ReadLaunchOptions(resolved_text, flags.scenario + " (with --set)");
  const std::string name =
      launch::ScenarioName(resolved, flags.scenario) + (replay ? "-replay" : "");
  const std::string source = replay ? launch::kReplaySource : launch::kSourceService;

  // Services to start, and every service whose section the scenario holds, check the file.
  const std::string bin_dir = flags.bin_dir.empty() ? OwnDirectory() : flags.bin_dir;
  std::vector<std::string> services;
  std::vector<std::pair<std::string, std::string>> checkers;
  for (const std::string& service : replay ? launch::kReplayServices : options.services) {
    const std::string exe = bin_dir + "/relplane-" + service;
    if (IsExecutable(exe)) {
      services.push_back(service);
      checkers.emplace_back(service, exe);
    } else if (flags.allow_missing) {
      launch::Say("warning: relplane-" + service + " is not built yet: running without it");
    } else {
      throw SetupError(exe + ": no such program (not built yet?); --allow-missing runs without it");
    }
  }
  for (const char* section : {"sim", "segmenter", "mapper", "logger"}) {
    const std::string exe = bin_dir + "/relplane-" + section;
    const bool listed = std::find(services.begin(), services.end(), section) != services.end();
    if (!listed && resolved[section] && IsExecutable(exe)) checkers.emplace_back(section, exe);
  }
  CheckConfig(checkers, flags.scenario, "");
  if (!flags.sets.empty()) {
    char temp[] = "/tmp/relplane-scenario-XXXXXX";
    const int fd = mkstemp(temp);
    if (fd < 0) throw SetupError("cannot create a temporary file in /tmp");
    close(fd);
    try {
      WriteFile(temp, resolved_text);
      CheckConfig(checkers, temp, " (in the scenario after the --set overrides)");
    } catch (...) {
      unlink(temp);
      throw;
    }
    unlink(temp);
  }
  const std::string lcm_logger = FindInPath("lcm-logger");
  if (lcm_logger.empty()) throw SetupError("lcm-logger not found in PATH (Debian: liblcm-bin)");
  const std::string lcm_logplayer = replay ? FindInPath("lcm-logplayer") : "";
  if (replay && lcm_logplayer.empty()) {
    throw SetupError("lcm-logplayer not found in PATH (Debian: liblcm-bin)");
  }
  const std::string url = ChooseUrl(flags);
  if (url.rfind("udpm://", 0) == 0 && !launch::HasMulticastRoute()) {
    throw SetupError(
        "no multicast route for the udpm bus: as root, ip route add 224.0.0.0/4 dev lo");
  }
  if (flags.check) {
    launch::Say(flags.scenario + ": OK");
    return launch::kExitOk;
  }

  const std::string run_dir = ChooseRunDir(flags, name);
  MakeDirectories(run_dir);
  if (replay && SameFile(run_dir + "/bus.lcmlog", flags.replay)) {
    throw SetupError(run_dir + ": the replay would record over the log it plays; choose --out");
  }
  const std::string scenario_file = run_dir + "/scenario.yaml";
  WriteFile(scenario_file, resolved_text);
  setenv("LCM_DEFAULT_URL", url.c_str(), 1);  // for the children and anything they start

  std::vector<launch::ChildSpec> children;
  for (const std::string& service : launch::StartOrder(services, source)) {
    children.push_back(launch::ServiceCommand(service, bin_dir, scenario_file, url, run_dir,
                                              options, flags.iterations));
  }
  if (replay) {
    children.push_back(launch::ReplayCommand(lcm_logplayer, url, flags.replay, flags.speed));
    services.push_back(source);
  }
  std::string listed;
  for (const std::string& service : services) listed += (listed.empty() ? "" : ", ") + service;
  launch::Say("scenario " + name + ": " + (listed.empty() ? "no services" : listed) +
              " + lcm-logger");
  launch::Say("bus " + url);
  launch::Say("run folder " + run_dir);

  launch::SupervisorOptions supervision;
  supervision.grace_s = options.grace_s;
  supervision.drain_s = options.drain_s;
  supervision.bus_port = launch::PortOfUrl(url).value_or(-1);
  supervision.source = source;
  const int code =
      launch::Supervise(launch::RecorderCommand(lcm_logger, url, run_dir), children, supervision);
  const char* verdict = code == launch::kExitOk            ? "done"
                        : code == launch::kExitInterrupted ? "interrupted"
                                                           : "FAILED";
  launch::Say(std::string(verdict) + ": run folder " + run_dir);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Runs a scenario: its services on a private LCM bus, recorded by lcm-logger.",
               "relplane-launch"};
  Flags flags;
  app.add_option("scenario", flags.scenario,
                 "Scenario YAML file (with --replay: default the log's RUN/scenario.yaml)");
  app.add_option("--out", flags.out,
                 "Run folder (default: runs/NAME-UTCTIME, or under "
                 "$RELPLANE_RUNS_DIR)");
  app.add_option("--set", flags.sets,
                 "Override a scenario value: key.path=value (YAML value; "
                 "lists as key[N]); repeatable")
      ->take_all();
  app.add_option("--lcm-url", flags.lcm_url, "Bus URL (default: a udpm port unique to the run)");
  app.add_option("--replay", flags.replay,
                 "Feed this recorded bus.lcmlog's SENSOR_POINTS, SIM_TRUTH and SIM_WORLD to "
                 "fresh segmenter, mapper and logger with lcm-logplayer, instead of the simulator");
  app.add_option("--speed", flags.speed, "Replay speed factor (1: as recorded)")
      ->check(CLI::PositiveNumber);
  app.add_option("--iterations", flags.iterations,
                 "Stop the simulator after N iterations (passed to relplane-sim)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--check", flags.check, "Validate the scenario with every service, start nothing");
  app.add_flag("--allow-missing", flags.allow_missing,
               "Run without services that are not built yet (with a warning)");
  app.add_option("--bin-dir", flags.bin_dir,
                 "Where relplane-<service> programs are (default: beside relplane-launch)");
  if (const auto code = relplane::cli::Parse(app, argc, argv)) return *code;
  try {
    return Launch(flags);
  } catch (const relplane::config::ConfigError& e) {
    std::cerr << e.what() << "\n";
  } catch (const SetupError& e) {
    std::cerr << e.what() << "\n";
  } catch (const YAML::Exception& e) {
    std::cerr << flags.scenario << ": " << e.what() << "\n";
  }
  return relplane::cli::kExitConfig;
}
