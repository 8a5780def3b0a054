#pragma once
// One child process in its own process group, its stdout and stderr read through pipes.
// The child is killed by the kernel if the launcher dies (PR_SET_PDEATHSIG), so a launcher
// killed with SIGKILL leaves no service behind.

#include <sys/types.h>

#include <string>

#include "lines.hpp"
#include "plan.hpp"

namespace relplane::launch {

class Child {
 public:
  // Forks and executes spec.argv with stdin from /dev/null. Throws std::runtime_error when the
  // program cannot be started (the reason from the failed exec included).
  explicit Child(const ChildSpec& spec);
  ~Child();
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  const std::string& Name() const { return name_; }
  pid_t Pid() const { return pid_; }
  // Pipe ends still open (-1 once the child closed its side and everything was read).
  int OutFd() const { return out_fd_; }
  int ErrFd() const { return err_fd_; }
  // Reads what is available on `fd` (one of the two above) and returns the completed lines;
  // at end of stream closes it and returns the rest.
  std::vector<std::string> ReadLines(int fd);

  bool Running() const { return !exited_; }
  int WaitStatus() const { return wait_status_; }
  void SetExited(int wait_status);
  // Signals the child's whole process group (harmless once it is gone).
  void SignalGroup(int sig) const;

 private:
  std::string name_;
  pid_t pid_ = -1;
  int out_fd_ = -1;
  int err_fd_ = -1;
  LineSplitter out_lines_;
  LineSplitter err_lines_;
  bool exited_ = false;
  int wait_status_ = 0;
};

// Runs argv to its end (at most `timeout_s`, then killed), returning its waitpid status and
// its stdout+stderr in `*output`. Throws std::runtime_error when it cannot be started.
int RunToEnd(const std::vector<std::string>& argv, double timeout_s, std::string* output);

}  // namespace relplane::launch
