#pragma once
// A child process for the logger and eval process tests: started with fork/exec, output into
// files, waited for with a time-out, killed on the way out if still running.

#include <sys/types.h>

#include <string>
#include <vector>

namespace relplane::testing {

// A fresh folder under the temporary directory, removed with its contents on destruction.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix);
  ~ScratchDir();
  const std::string& Path() const { return path_; }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

class Process {
 public:
  // Starts argv[0] with argv; stdout and stderr go to `out_file` and `err_file`.
  Process(const std::vector<std::string>& argv, const std::string& out_file,
          const std::string& err_file);
  ~Process();  // SIGKILLs a child still running (a failed test)
  pid_t Pid() const { return pid_; }
  void Signal(int signal) const;
  // Exit code, 128+N after signal N, or -1 when `timeout_s` passed first.
  int Wait(double timeout_s);

 private:
  pid_t pid_ = -1;
  bool done_ = false;
};

// Runs argv to its end (at most `timeout_s`); stdout and stderr into *out and *err.
int RunProcess(const std::vector<std::string>& argv, double timeout_s, std::string* out,
               std::string* err);

// Writes `text` to `path` (test set-up; throws when it cannot).
void WriteFileForTest(const std::string& path, const std::string& text);

// Waits up to `timeout_s` for `path` to exist.
bool WaitForFile(const std::string& path, double timeout_s);

}  // namespace relplane::testing
