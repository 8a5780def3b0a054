#include "bus_url.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace relplane::launch {

std::optional<int> ChoosePort(uint64_t seed, const std::function<bool(int)>& in_use) {
  constexpr uint64_t kCount = kLastRunPort - kFirstRunPort + 1;
  // splitmix64 spreads nearby seeds (consecutive pids) over the whole range.
  uint64_t z = seed + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  const uint64_t start = z % kCount;
  for (uint64_t i = 0; i < kCount; ++i) {
    const int port = kFirstRunPort + static_cast<int>((start + i) % kCount);
    if (!in_use || !in_use(port)) return port;
  }
  return std::nullopt;
}

std::string MakeUdpmUrl(int port, long recv_buf_bytes) {
  std::string url = "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
  if (recv_buf_bytes > 0) url += "&recv_buf_size=" + std::to_string(recv_buf_bytes);
  return url;
}

std::optional<int> PortOfUrl(const std::string& url) {
  const std::string scheme = "udpm://";
  if (url.compare(0, scheme.size(), scheme) != 0) return std::nullopt;
  const size_t colon = url.find(':', scheme.size());
  if (colon == std::string::npos) return std::nullopt;
  const size_t end = url.find_first_not_of("0123456789", colon + 1);
  const std::string digits =
      url.substr(colon + 1, end == std::string::npos ? end : end - colon - 1);
  if (digits.empty() || digits.size() > 5) return std::nullopt;
  const int port = std::stoi(digits);
  if (port <= 0 || port > 65535) return std::nullopt;
  return port;
}

std::vector<int> BoundUdpPorts(const std::string& proc_net_udp) {
  // Lines: "  sl  local_address rem_address   st ..." then "   0: 00000000:1DF3 00000000:0000 07".
  std::vector<int> ports;
  std::istringstream lines(proc_net_udp);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string slot, local;
    if (!(fields >> slot >> local) || slot.empty() || slot.back() != ':') continue;
    const size_t colon = local.find(':');
    if (colon == std::string::npos) continue;
    try {
      ports.push_back(std::stoi(local.substr(colon + 1), nullptr, 16));
    } catch (const std::exception&) {
      continue;
    }
  }
  return ports;
}

std::string ReadProcNetUdp() {
  std::ifstream in("/proc/net/udp");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool HasMulticastRoute() {
  // connect() on a UDP socket sends nothing; it only looks the route up.
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return true;  // cannot tell: let LCM report its own error
  sockaddr_in group{};
  group.sin_family = AF_INET;
  group.sin_port = htons(7667);
  inet_pton(AF_INET, "239.255.76.67", &group.sin_addr);
  const bool routed = connect(fd, reinterpret_cast<sockaddr*>(&group), sizeof group) == 0;
  close(fd);
  return routed;
}

long ReceiveBufferMax() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  long value = 0;
  return (in >> value) ? value : 0;
}

}  // namespace relplane::launch
