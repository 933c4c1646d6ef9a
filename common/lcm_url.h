// LCM URL helpers shared by the processes (no LCM needed): resolving the
// default URL and asking a UDP multicast URL for a larger kernel receive
// buffer.
#pragma once

#include <cstdint>
#include <string>

namespace mrsim {

// `url`, or when empty what LCM would use: $LCM_DEFAULT_URL, else
// udpm://239.255.76.67:7667?ttl=0.
std::string ResolveLcmUrl(const std::string& url);

// A udpm:// or mpudpm:// URL with recv_buf_size=`bytes` added (LCM leaves
// the kernel's default, 208 KB on Linux, which a burst of a few hundred
// small datagrams fills). URLs that already name a size, other transports
// and bytes <= 0 are returned resolved but unchanged.
std::string LcmUrlWithReceiveBuffer(const std::string& url, std::int64_t bytes);

// Why `url` (resolved) may not open and how to fix it, for the message of
// every program that cannot open LCM: a udpm:// group needs a multicast
// route (the commands that add one on loopback), a tcpq:// URL its hub.
std::string CannotOpenLcm(const std::string& url);

// The largest receive buffer an unprivileged SO_RCVBUF may ask for here
// (net.core.rmem_max; the kernel grants twice the request); 0 if unknown.
std::int64_t KernelReceiveBufferMax();

}  // namespace mrsim
