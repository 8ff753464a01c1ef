#pragma once
// Accepting only the samples a lock-step caller expects: its own run id and,
// when set, one exact step. Samples of another run (a stale process of an
// earlier run on the same domain) or of an unexpected step are dropped and
// counted, never delivered.
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "cosim_transport/topics.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim::transport {

class SampleFilter {
 public:
  explicit SampleFilter(std::uint64_t run_id) : run_id_(run_id) {}

  // Only samples of this step are accepted from now on.
  void expect_step(std::uint64_t step) { step_ = step; }
  // Any step is accepted from now on (run id still checked).
  void accept_any_step() { step_.reset(); }

  bool accept(const SampleHeader& header) {
    if (header.run_id != run_id_) {
      ++rejected_run_id_;
      return false;
    }
    if (step_ && header.step != *step_) {
      ++rejected_step_;
      return false;
    }
    ++accepted_;
    return true;
  }

  std::uint64_t run_id() const { return run_id_; }
  std::uint64_t accepted() const { return accepted_; }
  std::uint64_t rejected_run_id() const { return rejected_run_id_; }
  std::uint64_t rejected_step() const { return rejected_step_; }
  std::uint64_t rejected() const { return rejected_run_id_ + rejected_step_; }

 private:
  std::uint64_t run_id_;
  std::optional<std::uint64_t> step_;
  std::uint64_t accepted_ = 0;
  std::uint64_t rejected_run_id_ = 0;
  std::uint64_t rejected_step_ = 0;
};

// Waits up to `timeout` for the next sample the filter accepts; rejected ones
// are consumed and counted. False on timeout.
template <class T>
bool wait_for_accepted(Reader<T>& reader, SampleFilter& filter, T& out, std::chrono::microseconds timeout) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + timeout;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now());
    if (left.count() < 0 || !reader.wait_for(out, left)) return false;
    if (filter.accept(out.header)) return true;
  }
}

// Takes every sample received so far and appends the accepted ones to `out`;
// returns how many were appended.
template <class T>
std::size_t take_accepted(Reader<T>& reader, SampleFilter& filter, std::vector<T>& out) {
  std::vector<T> all;
  reader.take(all);
  std::size_t n = 0;
  for (auto& s : all) {
    if (filter.accept(s.header)) {
      out.push_back(std::move(s));
      ++n;
    }
  }
  return n;
}

}  // namespace cosim::transport
