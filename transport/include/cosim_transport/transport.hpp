#pragma once
// The one vendor-neutral transport interface: a Participant on a DDS domain
// makes typed Writers and Readers of the topics in topics.hpp. Fast DDS and
// Cyclone DDS implement it (transport/fast, transport/cyclone); callers pick a
// vendor at run time with make_participant(). No vendor header is included
// here or in any other public header of this library.
//
// Both backends set every QoS explicitly and identically (their defaults
// differ): RELIABLE, KEEP_LAST(depth), VOLATILE or TRANSIENT_LOCAL, XCDR1 data
// representation. Errors are reported as cosim::Error.
#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cosim_transport/topics.hpp"

namespace cosim::transport {

enum class Vendor { fast, cyclone };

// "fast" or "cyclone"; throws cosim::Error naming the accepted values otherwise,
// or if that vendor was left out of this build.
Vendor parse_vendor(const std::string& name);
const char* vendor_name(Vendor vendor);
// The vendors compiled into this build (COSIM_WITH_FASTDDS / COSIM_WITH_CYCLONEDDS).
std::vector<Vendor> available_vendors();

// A secured domain (OMG DDS Security 1.1 builtin plugins: PKI-DH
// authentication, Access-Permissions, AES-GCM-GMAC), from the folder that
// scripts/make_test_ca.sh writes: identity_ca.pem, permissions_ca.pem,
// governance.p7s, and per identity IDENTITY/cert.pem, key.pem, permissions.p7s.
// An empty directory is an open domain. docs/reliability.md, "DDS Security".
struct SecurityFiles {
  std::string directory;
  std::string identity;  // tyre, terrain, coupler or monitor: the subfolder of this participant
  bool enabled() const { return !directory.empty(); }
  // Absolute path of identity_ca.pem, permissions_ca.pem, governance.p7s, or
  // (for cert.pem, key.pem, permissions.p7s) of the identity's file.
  std::string path(const std::string& file) const;
};

struct TransportOptions {
  int domain_id = 0;  // 0..232
  // Interface name ("lo", "eth0") or IPv4 address all traffic is pinned to.
  // The default keeps everything on this machine.
  std::string network_interface = "lo";
  // IPv4 addresses discovery is sent to (unicast). Needed when multicast is off.
  std::vector<std::string> static_peers = {"127.0.0.1"};
  bool multicast = false;                    // multicast discovery and data
  int socket_buffer_bytes = 4 * 1024 * 1024;  // UDP send/receive buffers
  SecurityFiles security;                     // empty: an open domain
};

// Throws cosim::Error for an out-of-range domain, unknown interface, bad peer
// address, non-positive buffer size, or a security file that cannot be read. make_participant() calls it.
void validate(const TransportOptions& options);
// IPv4 address of options.network_interface (an address is returned as is).
std::string interface_address(const std::string& name_or_address);

enum class Durability { volatile_data, transient_local };

// Always RELIABLE and XCDR1; depth and durability per topic.
struct TopicQos {
  int depth = 16;  // KEEP_LAST depth of writer and reader history
  Durability durability = Durability::volatile_data;
  // Non-empty: the topic is TopicName<T> + "_" + channel, so that one type can
  // travel on several topics (the tyre's kinematics to the coupler, and the
  // same type with friction from the coupler to the terrain).
  std::string channel;
};
// The wire name of T's topic on `channel` (see TopicQos::channel).
template <class T> std::string topic_name(const TopicQos& qos) {
  return qos.channel.empty() ? std::string(TopicName<T>::value) : std::string(TopicName<T>::value) + "_" + qos.channel;
}
// SurfaceMesh: TRANSIENT_LOCAL keep-last 1 (late joiners get it);
// RunControl: volatile keep-last 64; per-step topics: volatile keep-last 16.
template <class T> TopicQos default_qos() { return {}; }
template <> inline TopicQos default_qos<SurfaceMesh>() { return {1, Durability::transient_local, {}}; }
template <> inline TopicQos default_qos<RunControl>() { return {64, Durability::volatile_data, {}}; }

// What writers and readers have in common.
class Endpoint {
 public:
  virtual ~Endpoint() = default;
  // Remote readers matched (writer) or remote writers matched (reader).
  virtual int matched_count() const = 0;
  // Writers: tell every matched reader which samples exist (an RTPS
  // heartbeat), so a reader that has just discovered this writer starts in
  // step with it before the first sample arrives. The start handshake calls
  // it; a no-op where the vendor needs nothing (readers, Cyclone writers).
  virtual void announce() {}
};

template <class T>
class Writer : public Endpoint {
 public:
  // Publishes one sample (blocks at most ~1 s if readers' histories are full);
  // throws cosim::Error if the vendor refuses it.
  virtual void write(const T& sample) = 0;
  int matched_readers() const { return matched_count(); }
  // True once every matched reader has acknowledged every sample written.
  virtual bool wait_for_acknowledgments(std::chrono::milliseconds timeout) = 0;
};

template <class T>
class Reader : public Endpoint {
 public:
  // Appends every sample received so far to `out` (oldest first); returns how many.
  virtual std::size_t take(std::vector<T>& out) = 0;
  // Waits for the next sample and moves it into `out`; false on timeout.
  virtual bool wait_for(T& out, std::chrono::microseconds timeout) = 0;
  int matched_writers() const { return matched_count(); }
};

// A DomainParticipant of one vendor. Writers and readers keep what they need
// of it alive, so they may outlive the Participant object.
class Participant {
 public:
  virtual ~Participant() = default;
  virtual Vendor vendor() const = 0;
  virtual int domain_id() const = 0;

  template <class T>
  std::unique_ptr<Writer<T>> create_writer(const TopicQos& qos = default_qos<T>()) {
    return make_writer(qos, static_cast<const T*>(nullptr));
  }
  template <class T>
  std::unique_ptr<Reader<T>> create_reader(const TopicQos& qos = default_qos<T>()) {
    return make_reader(qos, static_cast<const T*>(nullptr));
  }

 protected:
  // One pair per topic; the pointer argument only selects the overload.
  virtual std::unique_ptr<Writer<SurfaceMesh>> make_writer(const TopicQos&, const SurfaceMesh*) = 0;
  virtual std::unique_ptr<Writer<SurfaceKinematics>> make_writer(const TopicQos&, const SurfaceKinematics*) = 0;
  virtual std::unique_ptr<Writer<ContactLoads>> make_writer(const TopicQos&, const ContactLoads*) = 0;
  virtual std::unique_ptr<Writer<WheelState>> make_writer(const TopicQos&, const WheelState*) = 0;
  virtual std::unique_ptr<Writer<ForceSummary>> make_writer(const TopicQos&, const ForceSummary*) = 0;
  virtual std::unique_ptr<Writer<RunControl>> make_writer(const TopicQos&, const RunControl*) = 0;
  virtual std::unique_ptr<Reader<SurfaceMesh>> make_reader(const TopicQos&, const SurfaceMesh*) = 0;
  virtual std::unique_ptr<Reader<SurfaceKinematics>> make_reader(const TopicQos&, const SurfaceKinematics*) = 0;
  virtual std::unique_ptr<Reader<ContactLoads>> make_reader(const TopicQos&, const ContactLoads*) = 0;
  virtual std::unique_ptr<Reader<WheelState>> make_reader(const TopicQos&, const WheelState*) = 0;
  virtual std::unique_ptr<Reader<ForceSummary>> make_reader(const TopicQos&, const ForceSummary*) = 0;
  virtual std::unique_ptr<Reader<RunControl>> make_reader(const TopicQos&, const RunControl*) = 0;
};

// Creates a participant of `vendor` on options.domain_id, pinned to
// options.network_interface. Throws cosim::Error on bad options or if the
// vendor cannot create it.
std::unique_ptr<Participant> make_participant(Vendor vendor, const TransportOptions& options);

}  // namespace cosim::transport
