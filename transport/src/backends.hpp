#pragma once
// The factories each backend provides (internal to the library). Only the
// backends compiled in (cosim_transport/config.hpp) are defined.
#include <memory>
#include <string>

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

// `address`: the IPv4 address of options.network_interface, already resolved.
#if COSIM_TRANSPORT_HAS_FASTDDS
std::unique_ptr<Participant> make_fast_participant(const TransportOptions& options, const std::string& address);
#endif
#if COSIM_TRANSPORT_HAS_CYCLONEDDS
std::unique_ptr<Participant> make_cyclone_participant(const TransportOptions& options, const std::string& address);
#endif

}  // namespace cosim::transport
