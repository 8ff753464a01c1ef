#pragma once
// What the backends share (internal to the library): the participant over a
// vendor Domain, the take of every reader, and the factories each backend
// provides. Only the backends compiled in (cosim_transport/config.hpp) are defined.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cosim_transport/config.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim::transport {

// A Participant whose per-topic factories all forward to two templates of the
// backend, `writer_for<T>(qos)` and `reader_for<T>(qos)` (CRTP): the list of
// topics is written once here, not once per vendor.
template <class Backend>
class TopicParticipant : public Participant {
 protected:
  template <class T>
  std::unique_ptr<Writer<T>> writer(const TopicQos& q) { return static_cast<Backend&>(*this).template writer_for<T>(q); }
  template <class T>
  std::unique_ptr<Reader<T>> reader(const TopicQos& q) { return static_cast<Backend&>(*this).template reader_for<T>(q); }

  std::unique_ptr<Writer<SurfaceMesh>> make_writer(const TopicQos& q, const SurfaceMesh*) override { return writer<SurfaceMesh>(q); }
  std::unique_ptr<Writer<SurfaceKinematics>> make_writer(const TopicQos& q, const SurfaceKinematics*) override { return writer<SurfaceKinematics>(q); }
  std::unique_ptr<Writer<ContactLoads>> make_writer(const TopicQos& q, const ContactLoads*) override { return writer<ContactLoads>(q); }
  std::unique_ptr<Writer<WheelState>> make_writer(const TopicQos& q, const WheelState*) override { return writer<WheelState>(q); }
  std::unique_ptr<Writer<ForceSummary>> make_writer(const TopicQos& q, const ForceSummary*) override { return writer<ForceSummary>(q); }
  std::unique_ptr<Writer<RunControl>> make_writer(const TopicQos& q, const RunControl*) override { return writer<RunControl>(q); }
  std::unique_ptr<Reader<SurfaceMesh>> make_reader(const TopicQos& q, const SurfaceMesh*) override { return reader<SurfaceMesh>(q); }
  std::unique_ptr<Reader<SurfaceKinematics>> make_reader(const TopicQos& q, const SurfaceKinematics*) override { return reader<SurfaceKinematics>(q); }
  std::unique_ptr<Reader<ContactLoads>> make_reader(const TopicQos& q, const ContactLoads*) override { return reader<ContactLoads>(q); }
  std::unique_ptr<Reader<WheelState>> make_reader(const TopicQos& q, const WheelState*) override { return reader<WheelState>(q); }
  std::unique_ptr<Reader<ForceSummary>> make_reader(const TopicQos& q, const ForceSummary*) override { return reader<ForceSummary>(q); }
  std::unique_ptr<Reader<RunControl>> make_reader(const TopicQos& q, const RunControl*) override { return reader<RunControl>(q); }
};

// Reader<T>::take of a backend: every valid sample there is now, one by one
// from `take_one(sample)` (false when none is left), appended to `out`.
template <class T, class TakeOne>
std::size_t take_all(std::vector<T>& out, TakeOne take_one) {
  std::size_t n = 0;
  T s;
  while (take_one(s)) {
    out.push_back(std::move(s));
    ++n;
  }
  return n;
}

// A backend's Participant: one vendor Domain (its participant, publisher,
// subscriber and topics), shared by every writer and reader made on it, which
// keep it alive. The backends differ only in these types, not in this class.
template <Vendor kVendor, class Domain, template <class> class WriterOf, template <class> class ReaderOf>
class DomainParticipant final : public TopicParticipant<DomainParticipant<kVendor, Domain, WriterOf, ReaderOf>> {
 public:
  DomainParticipant(const TransportOptions& o, const std::string& address)
      : domain_(std::make_shared<Domain>(o, address)) {}
  Vendor vendor() const override { return kVendor; }
  int domain_id() const override { return domain_->domain_id(); }

  template <class T>
  std::unique_ptr<Writer<T>> writer_for(const TopicQos& q) { return std::make_unique<WriterOf<T>>(domain_, q); }
  template <class T>
  std::unique_ptr<Reader<T>> reader_for(const TopicQos& q) { return std::make_unique<ReaderOf<T>>(domain_, q); }

 private:
  std::shared_ptr<Domain> domain_;
};

// `address`: the IPv4 address of options.network_interface, already resolved.
#if COSIM_TRANSPORT_HAS_FASTDDS
std::unique_ptr<Participant> make_fast_participant(const TransportOptions& options, const std::string& address);
#endif
#if COSIM_TRANSPORT_HAS_CYCLONEDDS
std::unique_ptr<Participant> make_cyclone_participant(const TransportOptions& options, const std::string& address);
#endif

}  // namespace cosim::transport
