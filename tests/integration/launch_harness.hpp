#pragma once
// Helpers for tests that run relplane-launch as a real process: fake services written as
// shell scripts, the launcher started in the background, and a search for leftover processes.

#include <sys/types.h>

#include <string>
#include <vector>

namespace relplane::testing {

// A fresh temporary folder, removed with everything in it when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& Path() const { return path_; }

 private:
  std::string path_;
};

// Writes an executable `DIR/relplane-NAME` shell script. It answers --check-config with exit 0
// and otherwise runs `body` (sh), which may use $PIDS (a folder for pid files).
void WriteFakeService(const std::string& dir, const std::string& name, const std::string& body);

void WriteText(const std::string& path, const std::string& text);
std::string ReadText(const std::string& path);
bool Exists(const std::string& path);

// The launcher running in the background with stdout+stderr into a file.
class Launcher {
 public:
  Launcher(const std::vector<std::string>& args, const std::string& output_file);
  ~Launcher();  // kills it if still running (the test failed)
  pid_t Pid() const { return pid_; }
  // Waits up to `timeout_s` for it to end; returns its exit code, or -1 on time-out,
  // 128+N when a signal killed it.
  int Wait(double timeout_s);
  std::string Output() const { return ReadText(output_file_); }

 private:
  pid_t pid_ = -1;
  bool done_ = false;
  std::string output_file_;
};

// Runs the launcher to its end (up to `timeout_s`), returning its exit code; output in *output.
int RunLauncher(const std::vector<std::string>& args, double timeout_s, std::string* output);

// Live (not zombie) processes whose environment holds `entry` (e.g. LCM_DEFAULT_URL=...).
std::vector<pid_t> ProcessesWithEnvironment(const std::string& entry);

// Waits up to `timeout_s` until `path` exists and holds a line; returns its first number.
pid_t WaitForPidFile(const std::string& path, double timeout_s);

// True while `pid` is a live (not zombie) process.
bool Alive(pid_t pid);

// Path of relplane-launch (from the build) and the source tree.
std::string LauncherPath();
std::string SourceDir();

// A udpm URL on `port`, for tests that each own one.
std::string TestBusUrl(int port);

// The first match of the regular expression `pattern` (ECMAScript) in `text`: the whole match
// then each group, or nothing when none matches. The tests search with this rather than
// std::regex itself because each source that instantiates std::regex costs about 5 s of -O3.
std::vector<std::string> RegexSearch(const std::string& text, const std::string& pattern);

// `text` with the characters a regular expression reads as operators escaped.
std::string RegexEscape(const std::string& text);

}  // namespace relplane::testing
