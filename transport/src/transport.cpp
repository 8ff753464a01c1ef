// Vendor selection, option checks and the participant factory.
#include "cosim_transport/transport.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "backends.hpp"
#include "cosim/error.hpp"

namespace cosim::transport {

namespace {

bool is_ipv4(const std::string& s) {
  in_addr a{};
  return inet_pton(AF_INET, s.c_str(), &a) == 1;
}

const char* const kSecurityFiles[] = {"identity_ca.pem", "permissions_ca.pem", "governance.p7s",
                                      "cert.pem",        "key.pem",            "permissions.p7s"};

}  // namespace

const char* role_name(Role role) {
  switch (role) {
    case Role::any: return "any";
    case Role::tyre: return "tyre";
    case Role::terrain: return "terrain";
    case Role::coupler: return "coupler";
    case Role::monitor: return "monitor";
  }
  return "?";
}

const char* control_kind_name(ControlKind kind) {
  switch (kind) {
    case ControlKind::hello: return "hello";
    case ControlKind::ready: return "ready";
    case ControlKind::start: return "start";
    case ControlKind::stop: return "stop";
    case ControlKind::heartbeat: return "heartbeat";
    case ControlKind::failure: return "failure";
    case ControlKind::checkpoint_request: return "checkpoint_request";
    case ControlKind::checkpoint_at: return "checkpoint_at";
  }
  return "?";
}

std::uint64_t new_run_id() {
  std::random_device rd;
  std::uint64_t id = 0;
  while (id == 0) id = (static_cast<std::uint64_t>(rd()) << 32) ^ rd();
  return id;
}

const char* vendor_name(Vendor vendor) { return vendor == Vendor::fast ? "fast" : "cyclone"; }

std::vector<Vendor> available_vendors() {
  std::vector<Vendor> v;
#if COSIM_TRANSPORT_HAS_FASTDDS
  v.push_back(Vendor::fast);
#endif
#if COSIM_TRANSPORT_HAS_CYCLONEDDS
  v.push_back(Vendor::cyclone);
#endif
  return v;
}

Vendor parse_vendor(const std::string& name) {
  Vendor v;
  if (name == "fast") {
    v = Vendor::fast;
  } else if (name == "cyclone") {
    v = Vendor::cyclone;
  } else {
    throw Error("unknown DDS vendor '" + name + "': expected 'fast' (Fast DDS) or 'cyclone' (Cyclone DDS)");
  }
  for (Vendor a : available_vendors())
    if (a == v) return v;
  throw Error("DDS vendor '" + name + "' is not compiled into this build (see COSIM_WITH_FASTDDS / COSIM_WITH_CYCLONEDDS)");
}

std::string interface_address(const std::string& name_or_address) {
  if (is_ipv4(name_or_address)) return name_or_address;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) throw Error("cannot list network interfaces");
  std::string found, names;
  for (ifaddrs* i = list; i; i = i->ifa_next) {
    if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET) continue;
    names += std::string(names.empty() ? "" : ", ") + i->ifa_name;
    if (found.empty() && name_or_address == i->ifa_name) {
      char text[INET_ADDRSTRLEN] = {};
      inet_ntop(AF_INET, &reinterpret_cast<sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof text);
      found = text;
    }
  }
  freeifaddrs(list);
  if (found.empty())
    throw Error("network interface '" + name_or_address + "' has no IPv4 address (interfaces with one: " + names + ")");
  return found;
}

void validate(const TransportOptions& o) {
  // DDSI port mapping: 7400 + 250 * domain + offsets must stay below 65536.
  if (o.domain_id < 0 || o.domain_id > 232)
    throw Error("DDS domain id must be in 0..232 (got " + std::to_string(o.domain_id) + ")");
  if (o.socket_buffer_bytes <= 0)
    throw Error("socket buffer size must be > 0 bytes (got " + std::to_string(o.socket_buffer_bytes) + ")");
  for (const auto& p : o.static_peers)
    if (!is_ipv4(p)) throw Error("static peer '" + p + "' is not an IPv4 address");
  if (o.static_peers.empty() && !o.multicast)
    throw Error("no static peers and multicast off: participants could never discover each other");
  interface_address(o.network_interface);
  if (o.security.enabled()) {
    if (o.security.identity.empty()) throw Error("DDS Security: no identity given for " + o.security.directory);
    for (const char* file : kSecurityFiles) {
      const std::string path = o.security.path(file);
      if (!std::ifstream(path))
        throw Error("DDS Security: cannot read " + path +
                    " (make the folder with scripts/make_test_ca.sh, which writes every file a participant needs)");
    }
  }
}

std::string SecurityFiles::path(const std::string& file) const {
  std::error_code ec;
  std::filesystem::path base = std::filesystem::absolute(directory, ec);
  if (ec) base = directory;
  const bool shared = file == "identity_ca.pem" || file == "permissions_ca.pem" || file == "governance.p7s";
  return (shared ? base / file : base / identity / file).lexically_normal().string();
}

std::unique_ptr<Participant> make_participant(Vendor vendor, const TransportOptions& options) {
  validate(options);
  const std::string address = interface_address(options.network_interface);
  switch (vendor) {
    case Vendor::fast:
#if COSIM_TRANSPORT_HAS_FASTDDS
      return make_fast_participant(options, address);
#else
      break;
#endif
    case Vendor::cyclone:
#if COSIM_TRANSPORT_HAS_CYCLONEDDS
      return make_cyclone_participant(options, address);
#else
      break;
#endif
  }
  throw Error(std::string("DDS vendor '") + vendor_name(vendor) + "' is not compiled into this build");
}

}  // namespace cosim::transport
