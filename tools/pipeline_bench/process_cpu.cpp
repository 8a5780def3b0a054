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

}  // namespace relplane::bench
