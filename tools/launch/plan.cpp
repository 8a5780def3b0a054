#include "plan.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstring>
#include <sstream>

namespace relplane::launch {
namespace {
std::string FormatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}
}  // namespace

ChildSpec ServiceCommand(const std::string& name, const std::string& bin_dir,
                         const std::string& scenario_file, const std::string& url,
                         const std::string& run_dir, const LaunchOptions& options,
                         long iterations) {
  ChildSpec spec;
  spec.name = name;
  spec.argv = {bin_dir + "/relplane-" + name, "--config", scenario_file, "--lcm-url", url};
  if (name == "logger") spec.argv.insert(spec.argv.end(), {"--out", run_dir});
  if (name == "mapper") {
    spec.argv.insert(spec.argv.end(), {"--checkpoint", run_dir + "/" + kMapperJournal});
  }
  if (name == kSourceService && options.rate_hz >= 0.0) {
    spec.argv.insert(spec.argv.end(), {"--rate", FormatNumber(options.rate_hz)});
  }
  if (name == kSourceService && iterations >= 0) {
    spec.argv.insert(spec.argv.end(), {"--iterations", std::to_string(iterations)});
  }
  return spec;
}

std::string EveryChannelBut(const std::string& channel) {
  // A name differs from `channel` at some first character, is a proper prefix of it, or
  // extends it; an ERE cannot say "not", so each case is one alternative.
  std::string alternatives;
  const auto add = [&](const std::string& a) {
    alternatives += (alternatives.empty() ? "" : "|") + a;
  };
  for (size_t k = 0; k < channel.size(); ++k) {
    add(channel.substr(0, k) + "[^" + channel[k] + "].*");
    if (k > 0) add(channel.substr(0, k));
  }
  add(channel + ".+");
  return "(" + alternatives + ")";
}

bool UsesClouds(const std::string& name) { return name == "sim" || name == "segmenter"; }

ChildSpec WithCloudUrl(ChildSpec spec, const std::string& url, const std::string& cloud_url) {
  if (UsesClouds(spec.name) && cloud_url != url) {
    spec.argv.insert(spec.argv.end(), {"--cloud-url", cloud_url});
  }
  return spec;
}

std::vector<ChildSpec> RecorderCommands(const std::string& lcm_logger, const std::string& url,
                                        const std::string& cloud_url, const std::string& run_dir,
                                        const std::string& record) {
  if (record == kRecordNothing) return {};
  std::vector<ChildSpec> recorders = {RecorderCommand(lcm_logger, url, run_dir, record)};
  if (cloud_url != url && record == kRecordAll) {
    ChildSpec clouds = RecorderCommand(lcm_logger, cloud_url, run_dir);
    clouds.name = kCloudRecorder;
    clouds.argv.back() = run_dir + "/" + kCloudLog;
    recorders.push_back(std::move(clouds));
  }
  return recorders;
}

ChildSpec RecorderCommand(const std::string& lcm_logger, const std::string& url,
                          const std::string& run_dir, const std::string& record) {
  // The long form: the short -l flag is broken in LCM 1.3.1 (DESIGN.md).
  // --quiet: its once-a-second summary would drown the services' output; errors still show.
  ChildSpec recorder{"lcm-logger", {lcm_logger, "--lcm-url=" + url, "--force", "--quiet"}};
  if (record == kRecordWithoutClouds) {
    recorder.argv.push_back("--channel=" + EveryChannelBut("SENSOR_POINTS"));
  }
  recorder.argv.push_back(run_dir + "/bus.lcmlog");
  return recorder;
}

ChildSpec ReplayCommand(const std::string& lcm_logplayer, const std::string& url,
                        const std::string& log, double speed) {
  return {kReplaySource,
          {lcm_logplayer, "--speed=" + FormatNumber(speed), "--regexp=" + kReplayChannels,
           "--lcm-url=" + url, log}};
}

std::vector<ChildSpec> ReplayCommands(const std::string& lcm_logplayer, const std::string& url,
                                      const std::string& cloud_url, const std::string& log,
                                      double speed) {
  if (cloud_url == url) return {ReplayCommand(lcm_logplayer, url, log, speed)};
  ChildSpec sim = ReplayCommand(lcm_logplayer, url, log, speed);
  sim.name = kReplaySimSource;
  sim.argv[2] = "--regexp=" + kReplaySimChannels;
  ChildSpec clouds = ReplayCommand(lcm_logplayer, cloud_url, log, speed);
  clouds.argv[2] = "--regexp=^SENSOR_POINTS$";
  return {sim, clouds};
}

std::vector<std::string> StopOrder(const std::vector<std::string>& services,
                                   const std::string& source) {
  std::vector<std::string> order;
  for (const std::string& name :
       {source, std::string("segmenter"), std::string("mapper"), std::string("logger")}) {
    if (std::find(services.begin(), services.end(), name) != services.end()) order.push_back(name);
  }
  for (const std::string& name : services) {
    if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
  }
  return order;
}

std::vector<std::string> StartOrder(const std::vector<std::string>& services,
                                    const std::string& source) {
  std::vector<std::string> order;
  for (const std::string& name : services) {
    if (name != source) order.push_back(name);
  }
  if (std::find(services.begin(), services.end(), source) != services.end()) {
    order.push_back(source);
  }
  return order;
}

std::string DefaultRunDir(const std::string& root, const std::string& name, std::time_t now) {
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
  return root + "/" + name + "-" + stamp;
}

std::string DescribeExit(int wait_status) {
  if (WIFEXITED(wait_status)) return "exited with code " + std::to_string(WEXITSTATUS(wait_status));
  if (WIFSIGNALED(wait_status)) {
    const int sig = WTERMSIG(wait_status);
    const char* text = strsignal(sig);
    return "was killed by signal " + std::to_string(sig) +
           (text ? " (" + std::string(text) + ")" : "");
  }
  return "ended (status " + std::to_string(wait_status) + ")";
}

}  // namespace relplane::launch
