#pragma once
// The order of a participant's trials: every condition × item (2AFC pair or named
// stimulus) exactly `repetitions` times, and for 2AFC each pair in both orders equally
// often (counterbalanced), shuffled with a seed derived from the protocol's seed and the
// participant's ID. The same participant always gets the same order (so trial N of a
// resumed session is the trial N that was interrupted), different participants get
// different orders. The generator (SplitMix64, Fisher–Yates with an unbiased bounded
// draw) is written out here rather than std::shuffle, whose algorithm the standard leaves
// to the library: a schedule must not change with the compiler.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/study/study_protocol.hpp"

namespace mallet::study {

struct ScheduledTrial {
  int number = 0;  //!< 1-based, the CSV's `trial`
  StudyCondition condition = StudyCondition::both;
  int item = 0;          //!< index in StudyProtocol::pairs (2AFC) or ::named
  bool swapped = false;  //!< 2AFC: pair.b is shown first
};

//! FNV-1a of the ID mixed into the protocol seed.
std::uint64_t participant_seed(std::uint64_t protocol_seed, std::string_view participant);

std::vector<ScheduledTrial> balanced_schedule(const StudyProtocol& protocol, std::string_view participant);

//! The stimuli of a trial in presentation order (indices in StudyProtocol::stimuli).
std::vector<int> shown_stimuli(const StudyProtocol& protocol, const ScheduledTrial& trial);
//! The CSV's `stimuli` field: names in presentation order, joined by '|'.
std::string stimuli_text(const StudyProtocol& protocol, const ScheduledTrial& trial);
//! "1"/"2" (the interval holding the harder stimulus) or the material's name.
std::string correct_answer(const StudyProtocol& protocol, const ScheduledTrial& trial);
//! 2AFC: the pair's difference in B, percent; name_material: NaN.
double difference_pct(const StudyProtocol& protocol, const ScheduledTrial& trial);

//! SplitMix64: small, fast and fully specified.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  //! Uniform in [0, n), n > 0, without modulo bias (rejection).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % n);
    for (;;) {
      const std::uint64_t x = next();
      if (x < limit) return x % n;
    }
  }
  //! Uniform in [0, 1) with 53 bits.
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace mallet::study
