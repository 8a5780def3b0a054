#include "process_cpu.hpp"

#include <time.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace relplane::bench {

std::optional<double> ParseProcStatCpuSeconds(const std::string& stat, long ticks_per_second) {
  // "PID (COMM) STATE ..." where COMM may itself hold spaces and parentheses: the fields are
  // counted from the last ')'. utime and stime are fields 14 and 15 of proc(5), the 12th and
  // 13th after it.
  const size_t close = stat.rfind(')');
  if (close == std::string::npos || ticks_per_second <= 0) return std::nullopt;
  std::istringstream rest(stat.substr(close + 1));
  std::string field;
  for (int i = 0; i < 11; ++i) {
    if (!(rest >> field)) return std::nullopt;
  }
  long long utime = 0, stime = 0;
  if (!(rest >> utime >> stime) || utime < 0 || stime < 0) return std::nullopt;
  return static_cast<double>(utime + stime) / static_cast<double>(ticks_per_second);
}

std::optional<double> ProcessCpuSeconds(pid_t pid) {
  std::ifstream file("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(file, line)) return std::nullopt;
  return ParseProcStatCpuSeconds(line, sysconf(_SC_CLK_TCK));
}

double ThreadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) / 1e6;
}

std::optional<double> ParseMachineBusySeconds(const std::string& proc_stat,
                                             long ticks_per_second) {
  // "cpu  user nice system idle iowait irq softirq steal ..." in ticks (proc(5)).
  std::istringstream line(proc_stat.substr(0, proc_stat.find('\n')));
  std::string name;
  long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0;
  if (!(line >> name >> user >> nice >> system >> idle >> iowait >> irq >> softirq) ||
      name != "cpu" || ticks_per_second <= 0) {
    return std::nullopt;
  }
  long long steal = 0;
  line >> steal;  // absent on old kernels
  return static_cast<double>(user + nice + system + irq + softirq + steal) /
         static_cast<double>(ticks_per_second);
}

std::optional<double> MachineBusySeconds() {
  std::ifstream file("/proc/stat");
  std::stringstream text;
  text << file.rdbuf();
  return ParseMachineBusySeconds(text.str(), sysconf(_SC_CLK_TCK));
}

double LoadAverage() {
  std::ifstream file("/proc/loadavg");
  double load = -1.0;
  return (file >> load) ? load : -1.0;
}

}  // namespace relplane::bench
