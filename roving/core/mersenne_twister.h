// std::mt19937_64, draw for draw, with a discard that jumps instead of stepping: k draws ahead in
// milliseconds whatever k, where the standard's engine regenerates its state every 312 draws (5 ns
// a draw here: 16 s to reach the 3 billionth, as a shard of 10^9 area samples must).
//
// The jump is the polynomial method of Haramoto, Matsumoto, Nishimura, Panneton and L'Ecuyer,
// "Efficient jump ahead for F2-linear random number generators" (INFORMS J. Computing, 2008): the
// engine's step F is linear over GF(2) with minimal polynomial phi of degree 19937 on the states it
// reaches, so F^j s = g(F) s with g = t^j mod phi, evaluated by Horner's rule in 19937 steps.
#pragma once

#include <array>
#include <cstdint>

namespace roving {

class Mt19937_64 {
 public:
  using result_type = std::uint64_t;
  static constexpr std::size_t kWords = 312;

  explicit Mt19937_64(result_type seed = 5489u);

  result_type operator()() {
    if (next_ == kWords) regenerate();
    return temper(state_[next_++]);
  }
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }

  // Skips `count` draws: the next is the one std::mt19937_64's discard(count) would give.
  void discard(unsigned long long count);

 private:
  static result_type temper(result_type x);
  void regenerate();

  // As the standard's engine keeps it: the last block of 312 words, `next_` of them drawn.
  std::array<result_type, kWords> state_;
  std::size_t next_ = kWords;
};

}  // namespace roving
