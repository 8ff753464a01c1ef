// Fast DDS 2.9 backend: UDPv4 only (no shared memory, no data sharing), pinned
// to one interface, unicast discovery to the static peers, 4 MiB socket
// buffers, PREALLOCATED_WITH_REALLOC history memory (unbounded sequences).
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <map>
#include <mutex>

#include "../src/backends.hpp"
#include "cosim/error.hpp"
#include "fast_convert.hpp"

namespace cosim::transport {

namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

Duration_t to_duration(std::chrono::microseconds t) {
  if (t.count() < 0) t = std::chrono::microseconds(0);
  return Duration_t(static_cast<int32_t>(t.count() / 1000000), static_cast<uint32_t>((t.count() % 1000000) * 1000));
}

Locator_t udp_locator(const std::string& address) {
  Locator_t l;
  l.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(l, address);
  return l;
}

// Discovery reaches participant indices 0..kMaxParticipantIndex on each peer
// (Cyclone: MaxAutoParticipantIndex, the same value).
constexpr int kMaxParticipantIndex = 20;

bool udp_port_free(const std::string& address, int port) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return false;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  inet_pton(AF_INET, address.c_str(), &a.sin_addr);
  const bool free = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  close(fd);
  return free;
}

// Lowest participant index whose DDSI unicast ports (discovery and user
// traffic) are free on this machine, as Cyclone's "ParticipantIndex auto"
// picks it. Fast DDS would otherwise number participants by a per-process
// counter that never goes back, and after ten participants in one process
// (a test program) new ones are outside the peers' discovery range.
int free_participant_index(int domain_id, const std::string& address) {
  for (int index = 0; index <= kMaxParticipantIndex; ++index) {
    const int port = 7400 + 250 * domain_id + 10 + 2 * index;  // DDSI PB + DG*d + d1 + PG*i
    if (udp_port_free(address, port) && udp_port_free(address, port + 1)) return index;
  }
  throw Error("Fast DDS: no free participant index (0.." + std::to_string(kMaxParticipantIndex) + ") on domain " +
              std::to_string(domain_id) + ": too many participants on this machine");
}

// DDS Security 1.1 builtin plugins, configured by participant properties
// (Fast DDS documentation, "Security": dds.sec.* property names).
void add_security_properties(dds::DomainParticipantQos& q, const SecurityFiles& s) {
  auto& p = q.properties().properties();
  const auto file = [&](const char* name) { return "file://" + s.path(name); };
  p.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  p.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_ca", file("identity_ca.pem"));
  p.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_certificate", file("cert.pem"));
  p.emplace_back("dds.sec.auth.builtin.PKI-DH.private_key", file("key.pem"));
  p.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  p.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions_ca", file("permissions_ca.pem"));
  p.emplace_back("dds.sec.access.builtin.Access-Permissions.governance", file("governance.p7s"));
  p.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions", file("permissions.p7s"));
  p.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

// The DomainParticipant with one publisher and one subscriber; shared by the
// Participant object and every writer and reader made from it.
class Domain {
 public:
  Domain(const TransportOptions& o, const std::string& address) : domain_id_(o.domain_id) {
    dds::DomainParticipantQos q = dds::PARTICIPANT_QOS_DEFAULT;
    q.name("cosim");
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    udp->sendBufferSize = static_cast<uint32_t>(o.socket_buffer_bytes);
    udp->receiveBufferSize = static_cast<uint32_t>(o.socket_buffer_bytes);
    udp->interfaceWhiteList.push_back(address);
    udp->maxInitialPeersRange = kMaxParticipantIndex + 1;
    q.transport().use_builtin_transports = false;  // no shared memory: same path as across machines
    q.transport().user_transports.push_back(udp);
    q.transport().send_socket_buffer_size = static_cast<uint32_t>(o.socket_buffer_bytes);
    q.transport().listen_socket_buffer_size = static_cast<uint32_t>(o.socket_buffer_bytes);
    auto& builtin = q.wire_protocol().builtin;
    for (const auto& p : o.static_peers) builtin.initialPeersList.push_back(udp_locator(p));
    if (!o.multicast) {  // unicast locators only: no default multicast group
      builtin.metatrafficUnicastLocatorList.push_back(udp_locator(address));
      q.wire_protocol().default_unicast_locator_list.push_back(udp_locator(address));
    }
    if (o.security.enabled()) add_security_properties(q, o.security);
    {
      // Pick the index and bind its ports in one go: two participants created
      // at once in this process would otherwise pick the same index.
      std::lock_guard<std::mutex> lock(creation_mutex());
      q.wire_protocol().participant_id = free_participant_index(o.domain_id, address);
      participant_ = dds::DomainParticipantFactory::get_instance()->create_participant(o.domain_id, q);
    }
    if (!participant_)
      throw Error("Fast DDS: cannot create a participant on domain " + std::to_string(o.domain_id) + " (interface " +
                  address + (o.security.enabled() ? ", security files of '" + o.security.identity + "' in " +
                                                        o.security.directory + ": rejected, see the log above"
                                                  : std::string()) +
                  ")");
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    if (!publisher_ || !subscriber_) {
      release();
      throw Error("Fast DDS: cannot create a publisher/subscriber");
    }
  }
  ~Domain() { release(); }
  Domain(const Domain&) = delete;
  Domain& operator=(const Domain&) = delete;

  int domain_id() const { return domain_id_; }
  dds::Publisher* publisher() { return publisher_; }
  dds::Subscriber* subscriber() { return subscriber_; }

  // The topic of T, registering its type on first use.
  template <class T>
  dds::Topic* topic(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = topics_.find(name);
    if (it != topics_.end()) return it->second;
    dds::TypeSupport type(new typename fast::WireTypes<T>::PubSub());
    // One type may serve several topics (TopicQos::channel): register it once.
    if (participant_->find_type(type.get_type_name()).empty() &&
        type.register_type(participant_) != ReturnCode_t::RETCODE_OK)
      throw Error("Fast DDS: cannot register type " + type.get_type_name());
    dds::Topic* t = participant_->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    if (!t) throw Error("Fast DDS: cannot create topic " + name);
    topics_[name] = t;
    return t;
  }

 private:
  static std::mutex& creation_mutex() {
    static std::mutex m;
    return m;
  }

  void release() {
    if (!participant_) return;
    std::lock_guard<std::mutex> lock(creation_mutex());
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
    participant_ = nullptr;
  }

  int domain_id_;
  dds::DomainParticipant* participant_ = nullptr;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  std::mutex mutex_;
  std::map<std::string, dds::Topic*> topics_;
};

dds::DataRepresentationQosPolicy& representation(dds::DataWriterQos& q) { return q.representation(); }
dds::DataRepresentationQosPolicy& representation(dds::DataReaderQos& q) { return q.type_consistency().representation; }

// Reliability, history, durability and representation: identical to the Cyclone backend.
template <class Qos>
void set_common_qos(Qos& q, const TopicQos& t) {
  q.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  q.reliability().max_blocking_time = Duration_t(1, 0);
  q.durability().kind = t.durability == Durability::transient_local ? dds::TRANSIENT_LOCAL_DURABILITY_QOS
                                                                     : dds::VOLATILE_DURABILITY_QOS;
  q.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  q.history().depth = t.depth;
  q.resource_limits().max_instances = 1;  // keyless topics
  q.resource_limits().max_samples_per_instance = t.depth;
  q.resource_limits().max_samples = t.depth;
  q.resource_limits().allocated_samples = t.depth;
  representation(q).m_value = {dds::XCDR_DATA_REPRESENTATION};
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  q.data_sharing().off();
}

template <class T>
class FastWriter final : public Writer<T> {
 public:
  FastWriter(std::shared_ptr<Domain> d, const TopicQos& t) : domain_(std::move(d)), name_(topic_name<T>(t)) {
    dds::DataWriterQos q = domain_->publisher()->get_default_datawriter_qos();
    set_common_qos(q, t);
    q.publish_mode().kind = dds::SYNCHRONOUS_PUBLISH_MODE;
    q.reliable_writer_qos().times.heartbeatPeriod = Duration_t(0, 100000000);  // 100 ms, as Cyclone
    // Manual liveliness (infinite lease) only so that assert_liveliness() sends
    // a heartbeat: announce() below.
    q.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
    q.liveliness().lease_duration = eprosima::fastrtps::c_TimeInfinite;
    q.liveliness().announcement_period = eprosima::fastrtps::c_TimeInfinite;
    writer_ = domain_->publisher()->create_datawriter(domain_->topic<T>(name_), q);
    if (!writer_) throw Error("Fast DDS: cannot create a writer of " + name_);
  }
  ~FastWriter() override { domain_->publisher()->delete_datawriter(writer_); }

  void write(const T& sample) override {
    fast::to_wire(sample, wire_);
    if (!writer_->write(&wire_)) throw Error("Fast DDS: write to " + name_ + " failed");
  }
  int matched_count() const override {
    dds::PublicationMatchedStatus s;
    writer_->get_publication_matched_status(s);
    return s.current_count;
  }
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) override {
    return writer_->wait_for_acknowledgments(to_duration(timeout)) == ReturnCode_t::RETCODE_OK;
  }
  // Cyclone DDS 0.10 takes the first heartbeat it processes from a writer as
  // the start of the session and drops everything up to its last sequence
  // number, including a sample still being reassembled from fragments. Fast
  // sends one heartbeat when it matches a reader, often before that reader's
  // side has discovered the writer (so it is ignored), and the next only
  // 100 ms after data is unacknowledged: in lock-step that one can arrive in
  // the middle of a fragmented sample, which is then lost for good (seen as a
  // stall at step 4 of 5000-node runs, fast -> cyclone). A heartbeat sent once
  // both sides have matched puts the reader in step before the first sample.
  void announce() override { writer_->assert_liveliness(); }

 private:
  std::shared_ptr<Domain> domain_;
  std::string name_;
  dds::DataWriter* writer_ = nullptr;
  typename fast::WireTypes<T>::Wire wire_;
};

template <class T>
class FastReader final : public Reader<T> {
 public:
  FastReader(std::shared_ptr<Domain> d, const TopicQos& t) : domain_(std::move(d)), name_(topic_name<T>(t)) {
    dds::DataReaderQos q = domain_->subscriber()->get_default_datareader_qos();
    set_common_qos(q, t);
    reader_ = domain_->subscriber()->create_datareader(domain_->topic<T>(name_), q);
    if (!reader_) throw Error("Fast DDS: cannot create a reader of " + name_);
  }
  ~FastReader() override { domain_->subscriber()->delete_datareader(reader_); }

  std::size_t take(std::vector<T>& out) override { return take_all(out, [this](T& s) { return take_one(s); }); }
  bool wait_for(T& out, std::chrono::microseconds timeout) override {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
      if (take_one(out)) return true;
      const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0 || !reader_->wait_for_unread_message(to_duration(left))) return take_one(out);
    }
  }
  int matched_count() const override {
    dds::SubscriptionMatchedStatus s;
    reader_->get_subscription_matched_status(s);
    return s.current_count;
  }

 private:
  // Next valid sample (skips dispose/unregister notifications).
  bool take_one(T& out) {
    dds::SampleInfo info;
    while (reader_->take_next_sample(&wire_, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      fast::from_wire(wire_, out);
      return true;
    }
    return false;
  }

  std::shared_ptr<Domain> domain_;
  std::string name_;
  dds::DataReader* reader_ = nullptr;
  typename fast::WireTypes<T>::Wire wire_;
};

using FastParticipant = DomainParticipant<Vendor::fast, Domain, FastWriter, FastReader>;

}  // namespace

std::unique_ptr<Participant> make_fast_participant(const TransportOptions& options, const std::string& address) {
  return std::make_unique<FastParticipant>(options, address);
}

}  // namespace cosim::transport
