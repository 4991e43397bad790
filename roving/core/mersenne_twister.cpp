#include "roving/core/mersenne_twister.h"

#include <algorithm>
#include <vector>

namespace roving {
namespace {

using Word = std::uint64_t;
constexpr std::size_t kN = Mt19937_64::kWords, kM = 156;
constexpr Word kUpper = ~Word{0} << 31, kLower = ~kUpper, kTwist = 0xB5026F5AA96619E9ull;

// The standard's initialisation of the 312 words from a seed.
std::array<Word, kN> seeded(Word seed) {
  std::array<Word, kN> words;
  words[0] = seed;
  for (std::size_t i = 1; i < kN; ++i) words[i] = 6364136223846793005ull * (words[i - 1] ^ words[i - 1] >> 62) + i;
  return words;
}

// What a step adds to the word 156 on: the oldest word's upper 33 bits and its successor's lower 31.
Word twist(Word older, Word newer) {
  const Word y = (older & kUpper) | (newer & kLower);
  return (y >> 1) ^ ((y & 1) ? kTwist : 0);
}

// The engine's last 312 words as a sliding window, oldest at `oldest`: a step computes the next
// word from the oldest, its successor and the one 156 on, in the oldest's place.
struct Window {
  std::array<Word, kN> words{};
  std::size_t oldest = 0;

  void step() {
    words[oldest] = words[(oldest + kM) % kN] ^ twist(words[oldest], words[(oldest + 1) % kN]);
    oldest = (oldest + 1) % kN;
  }
  void add(const Window& other) {  // the step is linear over GF(2): states add by xor
    for (std::size_t i = 0; i < kN; ++i) words[(oldest + i) % kN] ^= other.words[(other.oldest + i) % kN];
  }
};

// A polynomial over GF(2), bit i the coefficient of t^i.
struct Polynomial {
  std::vector<Word> bits;
  explicit Polynomial(std::size_t degree_bound) : bits(degree_bound / 64 + 1, 0) {}
  bool at(std::size_t i) const { return bits[i / 64] >> (i % 64) & 1; }
  void flip(std::size_t i) { bits[i / 64] ^= Word{1} << (i % 64); }
  // this ^= other * t^shift
  void add_shifted(const Polynomial& other, std::size_t shift) {
    const std::size_t words = shift / 64, offset = shift % 64;
    for (std::size_t i = 0; i < other.bits.size() && i + words < bits.size(); ++i) {
      bits[i + words] ^= other.bits[i] << offset;
      if (offset != 0 && i + words + 1 < bits.size()) bits[i + words + 1] ^= other.bits[i] >> (64 - offset);
    }
  }
};

// The minimal polynomial of the engine's step (degree 19937) with its degree, by Berlekamp and
// Massey's algorithm over 2 x 19937 bits that the step gives: the lowest bit of each new word.
struct MinimalPolynomial {
  Polynomial phi{0};
  std::size_t degree = 0;
};

const MinimalPolynomial& minimal_polynomial() {
  static const MinimalPolynomial found = [] {
    constexpr std::size_t kDegree = 19937, kTerms = 2 * kDegree;
    Window w;
    w.words = seeded(5489u);  // any state the step has reached: the default seed's, one step on
    w.step();
    // The sequence backwards (bit kTerms - 1 - n is term n), so that the terms n - L .. n
    // that a discrepancy sums are a run of bits going up from kTerms - 1 - n.
    Polynomial reversed(kTerms + 64);
    for (std::size_t n = 0; n < kTerms; ++n) {
      w.step();
      if (w.words[(w.oldest + kN - 1) % kN] & 1) reversed.flip(kTerms - 1 - n);
    }
    const auto run_of_64 = [&](std::size_t from) {  // bits from .. from + 63 of reversed
      const std::size_t q = from / 64, r = from % 64;
      return r == 0 ? reversed.bits[q] : reversed.bits[q] >> r | reversed.bits[q + 1] << (64 - r);
    };
    Polynomial c(kTerms), b(kTerms);  // connection polynomials: current and before the last change
    c.flip(0);
    b.flip(0);
    std::size_t length = 0, since = 1;
    for (std::size_t n = 0; n < kTerms; ++n) {
      // The discrepancy: sum over i <= length of c_i s_(n - i) = c . reversed from kTerms-1-n.
      Word sum = 0;
      for (std::size_t k = 0; k <= length / 64; ++k) sum ^= c.bits[k] & run_of_64(kTerms - 1 - n + 64 * k);
      if (__builtin_parityll(sum) == 0) {
        ++since;
      } else if (2 * length <= n) {
        const Polynomial before = c;
        c.add_shifted(b, since);
        length = n + 1 - length;
        b = before;
        since = 1;
      } else {
        c.add_shifted(b, since);
        ++since;
      }
    }
    // phi(t) = t^length c(1 / t): the connection polynomial's coefficients reversed.
    MinimalPolynomial m;
    m.degree = length;
    m.phi = Polynomial(length);
    for (std::size_t i = 0; i <= length; ++i) {
      if (c.at(i)) m.phi.flip(length - i);
    }
    return m;
  }();
  return found;
}

// t^power mod phi, by squaring and multiplying by t along power's bits.
Polynomial power_of_t(unsigned long long power, const MinimalPolynomial& m) {
  const std::size_t degree = m.degree;
  Polynomial result(degree), square(2 * degree);
  result.flip(0);
  for (int bit = 63; bit >= 0; --bit) {
    // result^2: coefficient i goes to 2i (squaring is linear over GF(2)); then reduced.
    std::fill(square.bits.begin(), square.bits.end(), 0);
    for (std::size_t i = 0; i < degree; ++i) {
      if (result.at(i)) square.flip(2 * i);
    }
    for (std::size_t i = 2 * degree; i-- > degree;) {
      if (square.at(i)) square.add_shifted(m.phi, i - degree);
    }
    std::copy(square.bits.begin(), square.bits.begin() + result.bits.size(), result.bits.begin());
    if (power >> bit & 1) {  // times t
      Polynomial shifted(degree);
      shifted.add_shifted(result, 1);
      if (shifted.at(degree)) shifted.add_shifted(m.phi, 0);
      result = shifted;
    }
  }
  return result;
}

}  // namespace

Mt19937_64::Mt19937_64(result_type seed) : state_(seeded(seed)) {}

Mt19937_64::result_type Mt19937_64::temper(result_type x) {
  x ^= (x >> 29) & 0x5555555555555555ull;
  x ^= (x << 17) & 0x71D67FFFEDA60000ull;
  x ^= (x << 37) & 0xFFF7EEE000000000ull;
  return x ^ (x >> 43);
}

void Mt19937_64::regenerate() {
  // The window's 312 steps in place, as the standard's engine takes them: the word 156 on is an
  // old one for the first 156 and a new one after.
  std::size_t k = 0;
  for (; k < kN - kM; ++k) state_[k] = state_[k + kM] ^ twist(state_[k], state_[k + 1]);
  for (; k < kN - 1; ++k) state_[k] = state_[k + kM - kN] ^ twist(state_[k], state_[k + 1]);
  state_[kN - 1] = state_[kM - 1] ^ twist(state_[kN - 1], state_[0]);
  next_ = 0;
}

void Mt19937_64::discard(unsigned long long count) {
  if (count <= kWords - next_) {
    next_ += count;
    return;
  }
  // The block held is the window of the 312 words before the next block: `count` draws on, the
  // window must be that many steps further, and its next block drawn from.
  count -= kWords - next_;
  Window w;
  w.words = state_;
  // One step first: a seeded state carries 31 bits that no step reads, which phi does not cover.
  w.step();
  --count;
  constexpr unsigned long long kSteppedBelow = 1ull << 20;  // stepping: 10 ms; a jump: 20 ms or more
  if (count < kSteppedBelow) {
    for (; count > 0; --count) w.step();
  } else {
    const MinimalPolynomial& m = minimal_polynomial();
    const Polynomial g = power_of_t(count, m);
    Window sum;  // g(F) w by Horner's rule
    for (std::size_t i = m.degree; i-- > 0;) {
      sum.step();
      if (g.at(i)) sum.add(w);
    }
    w = sum;
  }
  for (std::size_t i = 0; i < kWords; ++i) state_[i] = w.words[(w.oldest + i) % kWords];
  next_ = kWords;
}

}  // namespace roving
