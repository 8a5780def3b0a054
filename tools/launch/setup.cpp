#include "setup.hpp"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>

#include "bus_url.hpp"
#include "child.hpp"
#include "plan.hpp"
#include "relplane/common/receive_buffer.hpp"

namespace relplane::launch {

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

std::string ChooseRunDir(const Request& request, const std::string& name) {
  if (!request.out.empty()) return request.out;
  const char* root = std::getenv("RELPLANE_RUNS_DIR");
  const std::string base = DefaultRunDir(root && *root ? root : "runs", name, std::time(nullptr));
  std::string dir = base;
  struct stat info {};
  for (int i = 2; stat(dir.c_str(), &info) == 0; ++i) dir = base + "-" + std::to_string(i);
  return dir;
}

namespace {

// A udpm URL on a free port other than `taken`.
std::string FreeRunUrl(int taken) {
  const std::vector<int> bound = BoundUdpPorts(ReadProcNetUdp());
  const uint64_t seed =
      (static_cast<uint64_t>(getpid()) << 32) ^
      static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  const std::optional<int> port = ChoosePort(seed, [&](int p) {
    return p == taken || std::find(bound.begin(), bound.end(), p) != bound.end();
  });
  if (!port) throw SetupError("no free UDP port for the run's bus");
  return MakeUdpmUrl(*port, 0);
}

}  // namespace

// Every bus of a run may carry clouds (the main one does when clouds share it, and lcm-logger
// reads each), so each asks for a receive buffer big enough for them.
std::string ChooseUrl(const Request& request) {
  return bus::CloudBusUrl(request.lcm_url.empty() ? FreeRunUrl(-1) : request.lcm_url);
}

std::string ChooseCloudUrl(const Request& request, const std::string& main_url) {
  if (!request.cloud_url.empty()) return bus::CloudBusUrl(request.cloud_url);
  if (!request.lcm_url.empty()) return main_url;
  return bus::CloudBusUrl(FreeRunUrl(PortOfUrl(main_url).value_or(-1)));
}

void CheckConfig(const std::vector<ServiceProgram>& services, const std::string& file,
                 const std::string& note) {
  for (const auto& [name, exe] : services) {
    std::string output;
    int status = 0;
    try {
      status = RunToEnd({exe, "--config", file, "--check-config"}, 20.0, &output);
    } catch (const std::exception& e) {
      throw SetupError(e.what());
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;
    while (!output.empty() && output.back() == '\n') output.pop_back();
    if (output.empty()) output = "relplane-" + name + " --check-config " + DescribeExit(status);
    throw SetupError(output + note);
  }
}

}  // namespace relplane::launch
