#include "relplane/common/receive_buffer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>

namespace relplane::bus {
namespace {

constexpr const char* kRmemMax = "/proc/sys/net/core/rmem_max";

long ReadRmemMax() {
  std::ifstream in(kRmemMax);
  long value = 0;
  return (in >> value) ? value : 0;
}

}  // namespace

long ReceiveBufferOfUrl(const std::string& url) {
  const std::string key = "recv_buf_size=";
  const size_t query = url.find('?');
  if (query == std::string::npos) return 0;
  for (size_t pos = query + 1; pos < url.size();) {
    const size_t end = std::min(url.find('&', pos), url.size());
    if (url.compare(pos, key.size(), key) == 0) {
      try {
        return std::stol(url.substr(pos + key.size(), end - pos - key.size()));
      } catch (const std::exception&) {
        return 0;
      }
    }
    pos = end + 1;
  }
  return 0;
}

std::string WithReceiveBuffer(const std::string& url, long bytes) {
  const std::string base = url.empty() ? kLcmDefaultUrl : url;
  if (base.rfind("udpm://", 0) != 0 || ReceiveBufferOfUrl(base) > 0) return base;
  const char separator = base.find('?') == std::string::npos ? '?' : '&';
  return base + separator + "recv_buf_size=" + std::to_string(bytes);
}

std::string EnsureReceiveBufferMax(long bytes) {
  const long cap = ReadRmemMax();
  if (cap >= bytes) return "";
  // Writable only by root (or in a network namespace of one's own).
  std::ofstream(kRmemMax) << bytes << "\n";
  if (ReadRmemMax() >= bytes) return "";
  return "net.core.rmem_max is " + std::to_string(cap) + " bytes, below the " +
         std::to_string(bytes) +
         " a bus of large point clouds needs: clouds may be lost (as root: sysctl -w "
         "net.core.rmem_max=" +
         std::to_string(bytes) + ")";
}

std::string CloudBusUrl(const std::string& url, long bytes) {
  const std::string resolved = WithReceiveBuffer(url, bytes);
  const long asked = ReceiveBufferOfUrl(resolved);
  if (asked > 0) {
    static bool warned = false;
    const std::string problem = EnsureReceiveBufferMax(asked);
    if (!problem.empty() && !warned) spdlog::warn("{}", problem);
    warned = warned || !problem.empty();
  }
  return resolved;
}

}  // namespace relplane::bus
