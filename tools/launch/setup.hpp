#pragma once
// Everything relplane-launch does before it starts a process: files, paths, the run folder,
// the bus URL and the services' own check of the scenario.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace relplane::launch {

// What the command line asks for (main.cpp).
struct Request {
  std::string scenario;
  std::string out;
  std::vector<std::string> sets;
  std::string lcm_url;
  std::string cloud_url;
  std::string bin_dir;
  std::string replay;  // a recorded bus.lcmlog to feed to fresh services
  double speed = 1.0;
  long iterations = -1;
  bool check = false;
  bool allow_missing = false;
};

// Every "stop before anything started" problem; one line, exit code 2.
struct SetupError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string ReadFile(const std::string& path);
void WriteFile(const std::string& path, const std::string& text);
bool IsExecutable(const std::string& path);
// The folder of the running executable (where relplane-<service> are built).
std::string OwnDirectory();
bool SameFile(const std::string& a, const std::string& b);
// `program` found in $PATH, "" when it is not.
std::string FindInPath(const std::string& program);
// mkdir -p.
void MakeDirectories(const std::string& path);

// --out, else RELPLANE_RUNS_DIR or runs/, NAME-UTCTIME, with -2, -3... when that exists.
std::string ChooseRunDir(const Request& request, const std::string& name);
// --lcm-url, else a udpm URL on a free port with the largest receive buffer allowed.
std::string ChooseUrl(const Request& request);
// The bus of SENSOR_POINTS: --cloud-url, else the main bus when --lcm-url was given (one URL
// for everything), else a udpm URL on another free port.
std::string ChooseCloudUrl(const Request& request, const std::string& main_url);

// A service and its executable.
using ServiceProgram = std::pair<std::string, std::string>;
// Runs `relplane-NAME --config FILE --check-config` for each; the first refusal is a
// SetupError with the service's own one-line message and `note` appended.
void CheckConfig(const std::vector<ServiceProgram>& services, const std::string& file,
                 const std::string& note);

}  // namespace relplane::launch
