#include "child.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace relplane::launch {
namespace {

void ClosePipe(int fds[2]) {
  for (int i = 0; i < 2; ++i) {
    if (fds[i] >= 0) close(fds[i]);
  }
}

// In the forked child: only async-signal-safe calls until exec.
[[noreturn]] void ExecChild(const ChildSpec& spec, char* const* argv, pid_t parent, int out_w,
                            int err_w, int report_w) {
  setpgid(0, 0);
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(127);  // the launcher died before prctl took effect
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, nullptr);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGCHLD, SIGQUIT}) signal(sig, SIG_DFL);
  const int null_fd = open("/dev/null", O_RDONLY);
  if (null_fd >= 0) dup2(null_fd, STDIN_FILENO);
  dup2(out_w, STDOUT_FILENO);
  dup2(err_w, STDERR_FILENO);
  execv(spec.argv[0].c_str(), argv);
  const int error = errno;
  (void)!write(report_w, &error, sizeof error);
  _exit(127);
}

}  // namespace

Child::Child(const ChildSpec& spec) : name_(spec.name) {
  if (spec.argv.empty()) throw std::runtime_error(spec.name + ": empty command");
  std::vector<char*> argv;
  for (const std::string& arg : spec.argv) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);

  int out[2] = {-1, -1}, err[2] = {-1, -1}, report[2] = {-1, -1};
  if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0 || pipe2(report, O_CLOEXEC) != 0) {
    const std::string reason = std::strerror(errno);
    ClosePipe(out), ClosePipe(err), ClosePipe(report);
    throw std::runtime_error(spec.name + ": cannot create pipes: " + reason);
  }
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) {
    const std::string reason = std::strerror(errno);
    ClosePipe(out), ClosePipe(err), ClosePipe(report);
    throw std::runtime_error(spec.name + ": fork failed: " + reason);
  }
  if (pid_ == 0) ExecChild(spec, argv.data(), parent, out[1], err[1], report[1]);

  setpgid(pid_, pid_);  // also here, so signalling the group works before the child ran
  close(out[1]), close(err[1]), close(report[1]);
  out_fd_ = out[0];
  err_fd_ = err[0];
  fcntl(out_fd_, F_SETFL, O_NONBLOCK);
  fcntl(err_fd_, F_SETFL, O_NONBLOCK);

  // The report pipe closes on a successful exec; an errno arrives when exec failed.
  int exec_errno = 0;
  ssize_t n;
  do {
    n = read(report[0], &exec_errno, sizeof exec_errno);
  } while (n < 0 && errno == EINTR);
  close(report[0]);
  if (n == static_cast<ssize_t>(sizeof exec_errno)) {
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    exited_ = true;
    close(out_fd_), close(err_fd_);
    out_fd_ = err_fd_ = -1;
    throw std::runtime_error("cannot start " + spec.argv[0] + ": " + std::strerror(exec_errno));
  }
}

Child::~Child() {
  if (out_fd_ >= 0) close(out_fd_);
  if (err_fd_ >= 0) close(err_fd_);
}

std::vector<std::string> Child::ReadLines(int fd) {
  LineSplitter& splitter = fd == out_fd_ ? out_lines_ : err_lines_;
  std::vector<std::string> lines;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n > 0) {
      for (std::string& line : splitter.Feed(buffer, static_cast<size_t>(n))) {
        lines.push_back(std::move(line));
      }
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return lines;
    // End of stream (or an error, treated alike): hand over the rest and close.
    for (std::string& line : splitter.Flush()) lines.push_back(std::move(line));
    close(fd);
    (fd == out_fd_ ? out_fd_ : err_fd_) = -1;
    return lines;
  }
}

void Child::SetExited(int wait_status) {
  exited_ = true;
  wait_status_ = wait_status;
}

void Child::SignalGroup(int sig) const {
  if (pid_ > 0) kill(-pid_, sig);
}

int RunToEnd(const std::vector<std::string>& argv, double timeout_s, std::string* output) {
  Child child({argv.empty() ? "" : argv[0], argv});
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000));
  bool killed = false;
  while (child.OutFd() >= 0 || child.ErrFd() >= 0) {
    pollfd fds[2] = {{child.OutFd(), POLLIN, 0}, {child.ErrFd(), POLLIN, 0}};
    poll(fds, 2, 100);
    for (const pollfd& p : fds) {
      if (p.fd >= 0 && p.revents != 0) {
        for (const std::string& line : child.ReadLines(p.fd)) *output += line + "\n";
      }
    }
    if (!killed && std::chrono::steady_clock::now() > deadline) {
      child.SignalGroup(SIGKILL);
      killed = true;
    }
  }
  int status = 0;
  while (waitpid(child.Pid(), &status, WNOHANG) == 0) {
    if (!killed && std::chrono::steady_clock::now() > deadline) {
      child.SignalGroup(SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  child.SetExited(status);
  child.SignalGroup(SIGKILL);  // nothing of it may outlive the check
  return status;
}

}  // namespace relplane::launch
