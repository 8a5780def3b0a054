#pragma once
// A bus private to one run. LCM 1.3.1 delivers every group address on a port to every socket
// bound to that port (DESIGN.md), so runs are told apart by UDP port, not by group address.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace relplane::launch {

constexpr int kFirstRunPort = 20000;  // above the well-known and registered services in use
constexpr int kLastRunPort = 59999;   // below Linux's ephemeral range (60999 is its end)

// A port in [kFirstRunPort, kLastRunPort] derived from `seed` (e.g. pid and time), skipping
// ports for which `in_use` says true. Returns std::nullopt when every port is taken.
std::optional<int> ChoosePort(uint64_t seed, const std::function<bool(int)>& in_use);

// udpm URL on `port`; `recv_buf_bytes` > 0 adds recv_buf_size so a large point cloud (many
// 64 KB fragments) fits in the socket buffer.
std::string MakeUdpmUrl(int port, long recv_buf_bytes);

// The port of a udpm:// URL, std::nullopt for other URLs or a missing port.
std::optional<int> PortOfUrl(const std::string& url);

// Local ports of the sockets listed in the text of /proc/net/udp (one entry per socket).
std::vector<int> BoundUdpPorts(const std::string& proc_net_udp);

// The text of /proc/net/udp ("" when unreadable).
std::string ReadProcNetUdp();

// Whether the kernel has a route for the udpm group (LCM cannot send without one).
bool HasMulticastRoute();

// net.core.rmem_max, the most a receive buffer may be set to; 0 when unknown.
long ReceiveBufferMax();

}  // namespace relplane::launch
