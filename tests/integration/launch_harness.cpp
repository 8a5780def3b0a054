#include "launch_harness.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace relplane::testing {
namespace {

using Clock = std::chrono::steady_clock;

void SleepMs(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

char ProcessState(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const size_t paren = text.rfind(')');
  return paren == std::string::npos || paren + 2 >= text.size() ? 0 : text[paren + 2];
}

}  // namespace

TempDir::TempDir() {
  char path[] = "/tmp/relplane-it-XXXXXX";
  if (!mkdtemp(path)) throw std::runtime_error("mkdtemp failed");
  path_ = path;
}

TempDir::~TempDir() {
  const std::string command = "rm -rf '" + path_ + "'";
  (void)!std::system(command.c_str());
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool Exists(const std::string& path) {
  struct stat info {};
  return stat(path.c_str(), &info) == 0;
}

void WriteFakeService(const std::string& dir, const std::string& name, const std::string& body) {
  const std::string path = dir + "/relplane-" + name;
  WriteText(path, "#!/bin/sh\nfor a in \"$@\"; do [ \"$a\" = --check-config ] && exit 0; done\n" +
                      body + "\n");
  chmod(path.c_str(), 0755);
}

Launcher::Launcher(const std::vector<std::string>& args, const std::string& output_file)
    : output_file_(output_file) {
  std::vector<std::string> argv = {LauncherPath()};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> raw;
  for (std::string& arg : argv) raw.push_back(arg.data());
  raw.push_back(nullptr);
  pid_ = fork();
  if (pid_ == 0) {
    const int fd = open(output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    execv(raw[0], raw.data());
    _exit(127);
  }
}

Launcher::~Launcher() {
  if (!done_ && pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
}

int Launcher::Wait(double timeout_s) {
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
  int status = 0;
  while (waitpid(pid_, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) return -1;
    SleepMs(20);
  }
  done_ = true;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int RunLauncher(const std::vector<std::string>& args, double timeout_s, std::string* output) {
  TempDir dir;
  Launcher launcher(args, dir.Path() + "/output.txt");
  const int code = launcher.Wait(timeout_s);
  *output = launcher.Output();
  return code;
}

std::vector<pid_t> ProcessesWithEnvironment(const std::string& entry) {
  std::vector<pid_t> found;
  DIR* proc = opendir("/proc");
  if (!proc) return found;
  while (dirent* e = readdir(proc)) {
    const pid_t pid = static_cast<pid_t>(std::atoi(e->d_name));
    if (pid <= 0 || pid == getpid()) continue;
    const std::string environ = ReadText("/proc/" + std::string(e->d_name) + "/environ");
    std::stringstream entries(environ);
    std::string item;
    while (std::getline(entries, item, '\0')) {
      if (item == entry) {
        if (Alive(pid)) found.push_back(pid);
        break;
      }
    }
  }
  closedir(proc);
  return found;
}

pid_t WaitForPidFile(const std::string& path, double timeout_s) {
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
  while (Clock::now() < deadline) {
    const std::string text = ReadText(path);
    if (!text.empty() && text.back() == '\n') return static_cast<pid_t>(std::atoi(text.c_str()));
    SleepMs(20);
  }
  return -1;
}

bool Alive(pid_t pid) {
  if (kill(pid, 0) != 0) return false;
  const char state = ProcessState(pid);
  return state != 0 && state != 'Z' && state != 'X';
}

std::string LauncherPath() { return RELPLANE_LAUNCH_PATH; }
std::string SourceDir() { return RELPLANE_SOURCE_DIR; }

std::string TestBusUrl(int port) {
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
}

std::vector<std::string> RegexSearch(const std::string& text, const std::string& pattern) {
  std::smatch match;
  if (!std::regex_search(text, match, std::regex(pattern))) return {};
  return std::vector<std::string>(match.begin(), match.end());
}

std::string RegexEscape(const std::string& text) {
  return std::regex_replace(text, std::regex(R"([.^$|()\[\]{}*+?\\])"), "\\$&");
}

}  // namespace relplane::testing
