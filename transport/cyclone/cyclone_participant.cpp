// Cyclone DDS 0.10 backend (C API): each domain is created from a config XML
// string (dds_create_domain) pinning traffic to one interface, unicast
// discovery to the static peers, 4 MiB socket buffers, 65500 B messages.
#include <dds/dds.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>

#include "../src/backends.hpp"
#include "cosim/error.hpp"
#include "cyclone_convert.hpp"

namespace cosim::transport {

namespace {

void check(dds_return_t rc, const std::string& what) {
  if (rc < 0) throw Error("Cyclone DDS: " + what + ": " + dds_strretcode(rc));
}

// The kernel caps SO_RCVBUF at net.core.rmem_max; Cyclone fails if it cannot
// get its "min", so ask for at most what the kernel allows.
long kernel_limit(const char* file, long wanted) {
  std::ifstream in(file);
  long limit = 0;
  return (in >> limit && limit > 0) ? std::min(limit, wanted) : wanted;
}

// DDS Security 1.1 builtin plugins, given in the participant's QoS properties
// (Cyclone DDS 0.10, "dds.sec.*"), which leaves the domain's XML configuration
// the same for open and secured participants; the plugins still act per domain
// and process (CycloneDomain::acquire). Debian installs them outside the
// loader's path, in the folder CMake found (COSIM_CYCLONE_SECURITY_DIR).
void set_security_properties(dds_qos_t* q, const SecurityFiles& s) {
  const auto file = [&](const char* name) { return "file://" + s.path(name); };
  const auto library = [&](const char* plugin, const char* name, const char* init, const char* fini) {
    const std::string prefix = std::string("dds.sec.") + plugin + ".library.";
    const std::string path = std::string(COSIM_CYCLONE_SECURITY_DIR) + "/libdds_security_" + name + ".so";
    dds_qset_prop(q, (prefix + "path").c_str(), path.c_str());
    dds_qset_prop(q, (prefix + "init").c_str(), init);
    dds_qset_prop(q, (prefix + "finalize").c_str(), fini);
  };
  library("auth", "auth", "init_authentication", "finalize_authentication");
  library("access", "ac", "init_access_control", "finalize_access_control");
  library("crypto", "crypto", "init_crypto", "finalize_crypto");
  dds_qset_prop(q, "dds.sec.auth.identity_ca", file("identity_ca.pem").c_str());
  dds_qset_prop(q, "dds.sec.auth.identity_certificate", file("cert.pem").c_str());
  dds_qset_prop(q, "dds.sec.auth.private_key", file("key.pem").c_str());
  dds_qset_prop(q, "dds.sec.access.permissions_ca", file("permissions_ca.pem").c_str());
  dds_qset_prop(q, "dds.sec.access.governance", file("governance.p7s").c_str());
  dds_qset_prop(q, "dds.sec.access.permissions", file("permissions.p7s").c_str());
}

std::string config_xml(const TransportOptions& o, const std::string& address) {
  const long rcv = kernel_limit("/proc/sys/net/core/rmem_max", o.socket_buffer_bytes);
  const long snd = kernel_limit("/proc/sys/net/core/wmem_max", o.socket_buffer_bytes);
  std::string x = "<CycloneDDS><Domain Id=\"any\"><General>";
  x += "<Interfaces><NetworkInterface address=\"" + address + "\"/></Interfaces>";
  x += std::string("<AllowMulticast>") + (o.multicast ? "true" : "false") + "</AllowMulticast>";
  x += "<MaxMessageSize>65500B</MaxMessageSize></General><Discovery>";
  x += "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>20</MaxAutoParticipantIndex><Peers>";
  for (const auto& p : o.static_peers) x += "<Peer address=\"" + p + "\"/>";
  x += "</Peers></Discovery><Internal>";
  x += "<SocketReceiveBufferSize min=\"" + std::to_string(rcv) + "B\"/>";
  x += "<SocketSendBufferSize min=\"" + std::to_string(snd) + "B\"/>";
  x += "</Internal>";
  if (const char* trace = std::getenv("COSIM_CYCLONEDDS_TRACE"))  // diagnostics: full Cyclone trace to this file
    x += std::string("<Tracing><Category>trace</Category><OutputFile>") + trace + "</OutputFile></Tracing>";
  x += "</Domain></CycloneDDS>";
  return x;
}

// A Cyclone domain is process-wide: the first participant on a domain id
// creates it from its configuration, later ones share it (and must ask for
// the same configuration); the last one to go deletes it.
class CycloneDomain {
 public:
  // `security`: the participant's identity certificate ("" open). Cyclone's
  // security plugins belong to the domain and act with the first participant's
  // identity and permissions for every participant of the process on it
  // (measured, docs/reliability.md: a second identity's grant was not applied,
  // and a second CA let an unauthenticated peer read), so one identity per
  // domain and process; the programs of a run have one participant each.
  static std::shared_ptr<CycloneDomain> acquire(int id, const std::string& config, const std::string& security) {
    static std::mutex mutex;
    static std::map<int, std::weak_ptr<CycloneDomain>> domains;
    std::lock_guard<std::mutex> lock(mutex);
    if (auto live = domains[id].lock()) {
      if (live->config_ != config)
        throw Error("Cyclone DDS: domain " + std::to_string(id) +
                    " is already in use in this process with other transport options");
      if (live->security_ != security)
        throw Error("Cyclone DDS: domain " + std::to_string(id) + " is already in use in this process " +
                    (live->security_.empty() ? "open" : "secured by " + live->security_) +
                    ": Cyclone's security plugins act with one identity for all the participants of a process on "
                    "a domain; give them the same identity, or put them in separate processes");
      return live;
    }
    const dds_entity_t handle = dds_create_domain(static_cast<dds_domainid_t>(id), config.c_str());
    check(handle, "cannot create domain " + std::to_string(id) + " (configuration " + config + ")");
    auto d = std::shared_ptr<CycloneDomain>(new CycloneDomain(handle, config, security));
    domains[id] = d;
    return d;
  }
  ~CycloneDomain() { dds_delete(handle_); }

 private:
  CycloneDomain(dds_entity_t h, std::string c, std::string s)
      : handle_(h), config_(std::move(c)), security_(std::move(s)) {}
  dds_entity_t handle_;
  std::string config_;
  std::string security_;
};

// The DomainParticipant and its topics; shared by the Participant object and
// every writer and reader made from it.
class Domain {
 public:
  Domain(const TransportOptions& o, const std::string& address)
      : domain_id_(o.domain_id), domain_(CycloneDomain::acquire(o.domain_id, config_xml(o, address),
                                       o.security.enabled() ? o.security.path("cert.pem") : "")) {
    dds_qos_t* qos = dds_create_qos();
    if (o.security.enabled()) set_security_properties(qos, o.security);
    participant_ = dds_create_participant(static_cast<dds_domainid_t>(o.domain_id), qos, nullptr);
    dds_delete_qos(qos);
    check(participant_, "cannot create a participant on domain " + std::to_string(o.domain_id) +
                            (o.security.enabled() ? " (security files of '" + o.security.identity + "' in " +
                                                        o.security.directory + ": rejected, see the log above)"
                                                  : std::string()));
  }
  ~Domain() { dds_delete(participant_); }
  Domain(const Domain&) = delete;
  Domain& operator=(const Domain&) = delete;

  int domain_id() const { return domain_id_; }
  dds_entity_t participant() const { return participant_; }

  template <class T>
  dds_entity_t topic(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = topics_.find(name);
    if (it != topics_.end()) return it->second;
    const dds_entity_t t =
        dds_create_topic(participant_, cyclone::WireTypes<T>::descriptor(), name.c_str(), nullptr, nullptr);
    check(t, "cannot create topic " + name);
    topics_[name] = t;
    return t;
  }

 private:
  int domain_id_;
  std::shared_ptr<CycloneDomain> domain_;
  dds_entity_t participant_ = 0;
  std::mutex mutex_;
  std::map<std::string, dds_entity_t> topics_;
};

// Reliability, history, durability and representation: identical to the Fast DDS backend.
struct Qos {
  explicit Qos(const TopicQos& t) : q(dds_create_qos()) {
    dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    dds_qset_durability(q, t.durability == Durability::transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL
                                                                        : DDS_DURABILITY_VOLATILE);
    dds_qset_history(q, DDS_HISTORY_KEEP_LAST, t.depth);
    dds_qset_resource_limits(q, t.depth, 1, t.depth);
    const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
    dds_qset_data_representation(q, 1, &xcdr1);
  }
  ~Qos() { dds_delete_qos(q); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  dds_qos_t* q;
};

template <class T>
class CycloneWriter final : public Writer<T> {
 public:
  CycloneWriter(std::shared_ptr<Domain> d, const TopicQos& t) : domain_(std::move(d)), name_(topic_name<T>(t)) {
    Qos qos(t);
    writer_ = dds_create_writer(domain_->participant(), domain_->topic<T>(name_), qos.q, nullptr);
    check(writer_, "cannot create a writer of " + name_);
  }
  ~CycloneWriter() override { dds_delete(writer_); }

  void write(const T& sample) override {
    typename cyclone::WireTypes<T>::Wire w{};
    cyclone::view(sample, w, scratch_);
    check(dds_write(writer_, &w), "write to " + name_);
  }
  int matched_count() const override {
    dds_publication_matched_status_t s{};
    dds_get_publication_matched_status(writer_, &s);
    return static_cast<int>(s.current_count);
  }
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) override {
    return dds_wait_for_acks(writer_, DDS_MSECS(timeout.count())) == DDS_RETCODE_OK;
  }

 private:
  std::shared_ptr<Domain> domain_;
  std::string name_;
  dds_entity_t writer_ = 0;
  cyclone::Scratch scratch_;
};

template <class T>
class CycloneReader final : public Reader<T> {
 public:
  CycloneReader(std::shared_ptr<Domain> d, const TopicQos& t) : domain_(std::move(d)), name_(topic_name<T>(t)) {
    Qos qos(t);
    reader_ = dds_create_reader(domain_->participant(), domain_->topic<T>(name_), qos.q, nullptr);
    check(reader_, "cannot create a reader of " + name_);
    const dds_entity_t cond = dds_create_readcondition(reader_, DDS_ANY_STATE);
    check(cond, "cannot create a read condition");
    waitset_ = dds_create_waitset(domain_->participant());
    check(waitset_, "cannot create a waitset");
    check(dds_waitset_attach(waitset_, cond, 0), "cannot attach to the waitset");
  }
  ~CycloneReader() override {
    dds_delete(waitset_);
    dds_delete(reader_);  // also deletes the read condition
  }

  std::size_t take(std::vector<T>& out) override { return take_all(out, [this](T& s) { return take_one(s); }); }
  bool wait_for(T& out, std::chrono::microseconds timeout) override {
    const dds_time_t deadline = dds_time() + DDS_USECS(std::max<long long>(0, timeout.count()));
    while (true) {
      if (take_one(out)) return true;
      const dds_duration_t left = deadline - dds_time();
      if (left <= 0) return false;
      check(dds_waitset_wait(waitset_, nullptr, 0, left), "waiting for data");
    }
  }
  int matched_count() const override {
    dds_subscription_matched_status_t s{};
    dds_get_subscription_matched_status(reader_, &s);
    return static_cast<int>(s.current_count);
  }

 private:
  // Next valid sample, read from a loan (skips dispose/unregister notifications).
  bool take_one(T& out) {
    while (true) {
      void* buffer[1] = {nullptr};
      dds_sample_info_t info[1];
      const dds_return_t n = dds_take(reader_, buffer, info, 1, 1);
      check(n, "take from " + name_);
      if (n == 0) return false;
      const bool valid = info[0].valid_data;
      if (valid) cyclone::from_wire(*static_cast<const typename cyclone::WireTypes<T>::Wire*>(buffer[0]), out);
      dds_return_loan(reader_, buffer, n);
      if (valid) return true;
    }
  }

  std::shared_ptr<Domain> domain_;
  std::string name_;
  dds_entity_t reader_ = 0;
  dds_entity_t waitset_ = 0;
};

using CycloneParticipant = DomainParticipant<Vendor::cyclone, Domain, CycloneWriter, CycloneReader>;

}  // namespace

std::unique_ptr<Participant> make_cyclone_participant(const TransportOptions& options, const std::string& address) {
  return std::make_unique<CycloneParticipant>(options, address);
}

}  // namespace cosim::transport
