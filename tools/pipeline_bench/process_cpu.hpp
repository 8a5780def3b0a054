#pragma once
// CPU time a process has used, from /proc/PID/stat. The benchmark divides each service's CPU
// time by the frames it handled: unlike latencies, that figure barely moves when other work
// shares the cores, and it bounds the rate the cores can hold at all.

#include <sys/types.h>

#include <optional>
#include <string>

namespace relplane::bench {

// User + system time in seconds from the text of a /proc/PID/stat file (all threads);
// std::nullopt when the text is not such a line. `ticks_per_second` is sysconf(_SC_CLK_TCK).
std::optional<double> ParseProcStatCpuSeconds(const std::string& stat, long ticks_per_second);

// The CPU seconds process `pid` has used so far; std::nullopt when it cannot be read (gone).
std::optional<double> ProcessCpuSeconds(pid_t pid);

// The CPU time the calling thread has used, milliseconds (nanosecond resolution).
double ThreadCpuMs();

// Busy seconds of all cores together (everything but idle and iowait) from the text of
// /proc/stat; std::nullopt when its first line is not the "cpu" line.
std::optional<double> ParseMachineBusySeconds(const std::string& proc_stat, long ticks_per_second);
// The same read now; std::nullopt when /proc/stat cannot be read.
std::optional<double> MachineBusySeconds();

// The 1-minute load average; negative when unknown.
double LoadAverage();

}  // namespace relplane::bench
