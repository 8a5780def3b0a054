#pragma once
// Receive buffers for buses that carry point clouds. A 640x480 cloud is ~3.7 MB, sent by LCM as
// ~57 UDP fragments of 64 KB; one fragment lost loses the cloud, and LCM's default socket
// buffer holds a few fragments only (DESIGN.md "LCM as Debian ships it"). Every process that
// receives clouds passes its bus URL through CloudBusUrl().

#include <string>

namespace relplane::bus {

// What a cloud receiver asks for: a few 640x480 clouds in flight.
constexpr long kCloudReceiveBufferBytes = 16l << 20;

// LCM 1.3.1's bus when no URL is given.
constexpr const char* kLcmDefaultUrl = "udpm://239.255.76.67:7667?ttl=0";

// The receive buffer `url` asks for in its recv_buf_size parameter; 0 when none.
long ReceiveBufferOfUrl(const std::string& url);

// `url` asking for a receive buffer of at least `bytes`: "" is LCM's default udpm URL, a udpm
// URL without recv_buf_size gets one; a URL that sets it, or is not udpm, is kept as it is.
std::string WithReceiveBuffer(const std::string& url, long bytes);

// The kernel caps every socket's buffer at net.core.rmem_max. Raises it to `bytes` when it is
// lower and the process may (root); returns "" when the cap is at least `bytes`, else one line
// saying what to do.
std::string EnsureReceiveBufferMax(long bytes);

// `url` (after ResolveUrl) ready for clouds: WithReceiveBuffer, then EnsureReceiveBufferMax for
// what it asks, the warning logged once per process when the cap stays below it.
std::string CloudBusUrl(const std::string& url, long bytes = kCloudReceiveBufferBytes);

}  // namespace relplane::bus
