#include "supervisor.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "bus_url.hpp"
#include "child.hpp"

namespace relplane::launch {
namespace {

using Clock = std::chrono::steady_clock;

int g_wake_pipe[2] = {-1, -1};
volatile sig_atomic_t g_stop_signals = 0;  // SIGINT/SIGTERM/SIGHUP received
volatile sig_atomic_t g_last_signal = 0;

void OnSignal(int sig) {
  const int saved = errno;
  if (sig != SIGCHLD) {
    g_stop_signals = g_stop_signals + 1;
    g_last_signal = sig;
  }
  const char byte = 0;
  (void)!write(g_wake_pipe[1], &byte, 1);
  errno = saved;
}

void InstallHandlers() {
  if (g_wake_pipe[0] < 0) {
    if (pipe2(g_wake_pipe, O_CLOEXEC | O_NONBLOCK) != 0) {
      throw std::runtime_error("cannot create the signal pipe");
    }
  }
  struct sigaction action {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGCHLD}) sigaction(sig, &action, nullptr);
  signal(SIGPIPE, SIG_IGN);  // a closed terminal must not kill the launcher before its children
}

Clock::time_point After(double seconds) {
  return Clock::now() + std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6));
}

// Processes whose parent is the launcher: its children and, as child subreaper, orphaned
// grandchildren.
std::vector<pid_t> OwnChildren() {
  std::vector<pid_t> pids;
  const pid_t self = getpid();
  DIR* proc = opendir("/proc");
  if (!proc) return pids;
  while (dirent* entry = readdir(proc)) {
    const pid_t pid = static_cast<pid_t>(std::atoi(entry->d_name));
    if (pid <= 0) continue;
    std::ifstream stat("/proc/" + std::string(entry->d_name) + "/stat");
    std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
    const size_t paren = text.rfind(')');  // the command name may hold spaces and parentheses
    if (paren == std::string::npos) continue;
    char state = 0;
    int ppid = 0;
    if (std::sscanf(text.c_str() + paren + 1, " %c %d", &state, &ppid) == 2 && ppid == self) {
      pids.push_back(pid);
    }
  }
  closedir(proc);
  return pids;
}

class Run {
 public:
  explicit Run(const SupervisorOptions& options) : options_(options) {}

  int Execute(const std::vector<ChildSpec>& recorders, const std::vector<ChildSpec>& services);

 private:
  Child* Start(const ChildSpec& spec);
  void WaitForSubscribers(size_t expected);
  // Polls output, signals and child ends for at most `seconds`; returns early once `done`.
  void PumpUntil(Clock::time_point deadline, const std::function<bool()>& done);
  void PumpOnce(int timeout_ms);
  // Collects ended children; false once the launcher has no child process at all.
  bool Reap();
  void OnExit(Child& child);
  // True when `child` crashed and the restart policy starts it again (after Reap).
  bool ScheduleRestart(const Child& child);
  void StartPendingRestarts();
  void Fail(const std::string& message);
  void StopChild(Child& child);
  void StopAll();
  void Sweep();
  Child* Find(const std::string& name);
  bool IsRecorder(const std::string& name) const;
  bool IsSource(const std::string& name) const;
  void Print(const Child& child, bool is_err, const std::string& line) const;

  SupervisorOptions options_;
  std::vector<std::unique_ptr<Child>> children_;  // a restarted service appears again, later
  std::map<std::string, ChildSpec> specs_;        // command lines, to restart with
  std::map<std::string, int> restarts_;           // restarts so far per service
  std::vector<std::string> pending_restarts_;
  std::vector<std::string> stop_requested_;  // names we asked to stop
  std::vector<std::string> recorders_;       // names of the recorders
  size_t name_width_ = 0;
  bool stopping_ = false;
  bool failed_ = false;
  bool interrupted_ = false;
  bool forced_ = false;
  bool draining_ = false;
  Clock::time_point drain_end_;
  sig_atomic_t signals_seen_ = 0;
};

Child* Run::Start(const ChildSpec& spec) {
  specs_[spec.name] = spec;
  try {
    children_.push_back(std::make_unique<Child>(spec));
    return children_.back().get();
  } catch (const std::exception& e) {
    Fail(e.what());
    return nullptr;
  }
}

// The latest process of that name (a restarted service's earlier ones have ended).
Child* Run::Find(const std::string& name) {
  for (auto it = children_.rbegin(); it != children_.rend(); ++it) {
    if ((*it)->Name() == name) return it->get();
  }
  return nullptr;
}

bool Run::IsRecorder(const std::string& name) const {
  return std::find(recorders_.begin(), recorders_.end(), name) != recorders_.end();
}

bool Run::IsSource(const std::string& name) const {
  return name == options_.source || std::find(options_.side_sources.begin(),
                                              options_.side_sources.end(),
                                              name) != options_.side_sources.end();
}

void Run::Print(const Child& child, bool is_err, const std::string& line) const {
  std::string prefix = "[" + child.Name() + "]";
  prefix.resize(std::max(prefix.size(), name_width_ + 2), ' ');
  const std::string text = prefix + " " + line + "\n";
  FILE* stream = is_err ? stderr : stdout;
  std::fwrite(text.data(), 1, text.size(), stream);
  std::fflush(stream);
}

void Run::Fail(const std::string& message) {
  Say(message);
  failed_ = true;
  stopping_ = true;
}

void Run::OnExit(Child& child) {
  const int status = child.WaitStatus();
  const bool asked = std::find(stop_requested_.begin(), stop_requested_.end(), child.Name()) !=
                     stop_requested_.end();
  if (asked) {
    // Dying of the SIGINT/SIGTERM we sent is a clean stop; an error code or a crash while
    // stopping is a failure (the logger writes its files then).
    const bool clean =
        (WIFEXITED(status) && WEXITSTATUS(status) == 0) ||
        (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM));
    if (clean) {
      Say("stopped " + child.Name());
    } else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) {
      Say("warning: " + child.Name() + " had to be killed");
    } else {
      Fail("error: " + child.Name() + " " + DescribeExit(status) + " while stopping");
    }
    return;
  }
  if (child.Name() == options_.source && !stopping_ && !draining_ && WIFEXITED(status) &&
      WEXITSTATUS(status) == 0) {
    Say(child.Name() + " finished; letting the pipeline drain for " +
        std::to_string(options_.drain_s).substr(0, 4) + " s");
    draining_ = true;
    drain_end_ = After(options_.drain_s);
    return;
  }
  if (IsSource(child.Name()) && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    Say(child.Name() + " finished");
    return;
  }
  if (ScheduleRestart(child)) return;
  Fail("error: " + child.Name() + " " + DescribeExit(status) + " unexpectedly");
}

bool Run::ScheduleRestart(const Child& child) {
  const int status = child.WaitStatus();
  const bool crashed = WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0);
  if (!crashed || stopping_ || !options_.restart.Covers(child.Name())) return false;
  int& count = restarts_[child.Name()];
  const std::string limit = std::to_string(options_.restart.max_restarts);
  if (count >= options_.restart.max_restarts) {
    Say("error: " + child.Name() + " " + DescribeExit(status) + " after " + limit +
        " restarts (launch.restart.max_restarts): giving up");
    return false;
  }
  ++count;
  Say("warning: " + child.Name() + " " + DescribeExit(status) + "; restarting it (restart " +
      std::to_string(count) + " of " + limit + ")");
  pending_restarts_.push_back(child.Name());
  return true;
}

void Run::StartPendingRestarts() {
  // Started outside Reap, which walks children_.
  std::vector<std::string> names;
  names.swap(pending_restarts_);
  for (const std::string& name : names) {
    if (stopping_) return;
    Start(specs_.at(name));
  }
}

bool Run::Reap() {
  int status = 0;
  pid_t pid;
  while ((pid = waitpid(-1, &status, WNOHANG)) > 0) {
    for (auto& child : children_) {
      if (child->Pid() == pid && child->Running()) {
        child->SetExited(status);
        OnExit(*child);
      }
    }
    // Other pids are orphaned grandchildren adopted by the launcher (subreaper): just reaped.
  }
  return !(pid < 0 && errno == ECHILD);
}

void Run::PumpOnce(int timeout_ms) {
  std::vector<pollfd> fds = {{g_wake_pipe[0], POLLIN, 0}};
  std::vector<std::pair<Child*, bool>> owners = {{nullptr, false}};
  for (auto& child : children_) {
    if (child->OutFd() >= 0)
      fds.push_back({child->OutFd(), POLLIN, 0}), owners.push_back({child.get(), false});
    if (child->ErrFd() >= 0)
      fds.push_back({child->ErrFd(), POLLIN, 0}), owners.push_back({child.get(), true});
  }
  poll(fds.data(), fds.size(), timeout_ms);
  char drain[64];
  while (read(g_wake_pipe[0], drain, sizeof drain) > 0) {
  }
  for (size_t i = 1; i < fds.size(); ++i) {
    if (fds[i].revents == 0) continue;
    Child* child = owners[i].first;
    for (const std::string& line : child->ReadLines(fds[i].fd))
      Print(*child, owners[i].second, line);
  }
  Reap();
  StartPendingRestarts();

  const sig_atomic_t seen = g_stop_signals;
  if (seen != signals_seen_) {
    signals_seen_ = seen;
    if (!interrupted_) {
      interrupted_ = true;
      stopping_ = true;
      Say(std::string("interrupted (") + strsignal(g_last_signal) + "): stopping");
    } else if (!forced_) {
      forced_ = true;
      Say("interrupted again: killing every child now");
      for (auto& child : children_) {
        if (child->Running()) child->SignalGroup(SIGKILL);
      }
    }
  }
}

void Run::PumpUntil(Clock::time_point deadline, const std::function<bool()>& done) {
  while (!(done && done())) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return;
    PumpOnce(static_cast<int>(std::min<int64_t>(left.count(), 100)));
  }
}

void Run::WaitForSubscribers(size_t expected) {
  if (options_.bus_ports.empty()) {
    PumpUntil(After(0.3), [&] { return stopping_; });
    return;
  }
  bool ready = false;
  PumpUntil(After(options_.ready_timeout_s), [&] {
    // Each subscriber binds one of the run's ports once.
    size_t bound = 0;
    for (int port : BoundUdpPorts(ReadProcNetUdp())) {
      bound += std::count(options_.bus_ports.begin(), options_.bus_ports.end(), port) > 0;
    }
    ready = bound >= expected;
    return ready || stopping_;
  });
  if (!ready && !stopping_) {
    Say("warning: only some subscribers joined the bus after " +
        std::to_string(options_.ready_timeout_s).substr(0, 3) + " s; going on");
  }
  // A socket is bound just before it joins the multicast group and its reader starts.
  PumpUntil(After(0.1), [&] { return stopping_; });
}

void Run::StopChild(Child& child) {
  if (!child.Running()) return;
  stop_requested_.push_back(child.Name());
  const std::pair<int, const char*> steps[] = {
      {SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGKILL, "SIGKILL"}};
  for (const auto& [sig, name] : steps) {
    if (!child.Running()) return;
    if (sig != SIGINT) {
      Say("warning: " + child.Name() + " still running " +
          std::to_string(options_.grace_s).substr(0, 4) + " s after the last signal; sending " +
          name);
    }
    child.SignalGroup(forced_ ? SIGKILL : sig);
    PumpUntil(After(options_.grace_s), [&] { return !child.Running(); });
  }
}

void Run::StopAll() {
  std::vector<std::string> names;
  for (auto& child : children_) {
    if (!IsRecorder(child->Name())) names.push_back(child->Name());
  }
  // The side sources with the source, before the pipeline.
  std::vector<std::string> order = options_.side_sources;
  for (const std::string& name : StopOrder(names, options_.source)) order.push_back(name);
  for (const std::string& name : order) {
    if (Child* child = Find(name)) StopChild(*child);
  }
  // lcm-logger drops what it has not written yet on SIGINT: let the recorders catch up first.
  PumpUntil(After(forced_ ? 0.0 : options_.recorder_drain_s), [&] { return forced_; });
  for (const std::string& name : recorders_) {
    if (Child* recorder = Find(name)) StopChild(*recorder);
  }
}

void Run::Sweep() {
  // Grandchildren left in a child's group, and orphans the launcher adopted, go too.
  for (auto& child : children_) child->SignalGroup(SIGKILL);
  const auto deadline = After(2.0);
  for (;;) {
    for (pid_t pid : OwnChildren()) kill(pid, SIGKILL);
    if (!Reap() || Clock::now() > deadline) break;
    PumpOnce(20);
  }
  // Output still in the pipes.
  PumpUntil(After(0.5), [&] {
    return std::all_of(children_.begin(), children_.end(),
                       [](const auto& c) { return c->OutFd() < 0 && c->ErrFd() < 0; });
  });
}

int Run::Execute(const std::vector<ChildSpec>& recorders, const std::vector<ChildSpec>& services) {
  InstallHandlers();
  // Orphaned grandchildren are re-parented to the launcher, which then kills and reaps them.
  prctl(PR_SET_CHILD_SUBREAPER, 1);
  for (const ChildSpec& spec : recorders) {
    recorders_.push_back(spec.name);
    name_width_ = std::max(name_width_, spec.name.size());
  }
  for (const ChildSpec& spec : services) name_width_ = std::max(name_width_, spec.name.size());

  size_t subscribers = 0;
  for (const ChildSpec& spec : recorders) {
    if (!stopping_ && Start(spec)) ++subscribers;
  }
  if (!recorders.empty()) WaitForSubscribers(subscribers);
  bool sources_started = false;
  for (const ChildSpec& spec : services) {
    if (stopping_) break;
    const bool source = IsSource(spec.name);
    if (source && !sources_started) {
      WaitForSubscribers(subscribers);
      sources_started = true;
      if (stopping_) break;
    }
    if (Start(spec) && !source) ++subscribers;
  }
  if (!stopping_ && (services.empty() || services.back().name != options_.source)) {
    WaitForSubscribers(subscribers);
  }

  PumpUntil(Clock::time_point::max(),
            [&] { return stopping_ || (draining_ && Clock::now() >= drain_end_); });
  StopAll();
  Sweep();
  if (!restarts_.empty()) {
    std::string counts;
    for (const auto& [name, count] : restarts_) {
      counts += (counts.empty() ? "" : ", ") + name + " " + std::to_string(count);
    }
    Say("restarts: " + counts);
  }
  if (failed_) return kExitFailed;
  return interrupted_ ? kExitInterrupted : kExitOk;
}

}  // namespace

void Say(const std::string& message) {
  const std::string text = "[launch] " + message + "\n";
  std::fwrite(text.data(), 1, text.size(), stderr);
  std::fflush(stderr);
}

int Supervise(const std::vector<ChildSpec>& recorders, const std::vector<ChildSpec>& services,
              const SupervisorOptions& options) {
  return Run(options).Execute(recorders, services);
}

}  // namespace relplane::launch
