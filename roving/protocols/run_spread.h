// A protocol's figures over its runs (DTU's shuffles, Tanks and Temples' registrations, one per
// seed): each figure's mean, sample standard deviation, least and largest.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace roving {

struct Spread {
  double mean = 0, sd = 0, min = 0, max = 0;
};

template <class Run>
Spread spread_of(const std::vector<Run>& runs, double Run::*figure) {
  Spread s{0, 0, runs.front().*figure, runs.front().*figure};
  for (const Run& run : runs) {
    s.mean += run.*figure / runs.size();
    s.min = std::min(s.min, run.*figure);
    s.max = std::max(s.max, run.*figure);
  }
  for (const Run& run : runs) s.sd += (run.*figure - s.mean) * (run.*figure - s.mean);
  s.sd = runs.size() > 1 ? std::sqrt(s.sd / (runs.size() - 1)) : 0;
  return s;
}

// Each figure's spread over the runs as JSON (null for one run).
template <class Run, std::size_t N>
nlohmann::json spread_json(const std::vector<Run>& runs,
                           const std::array<std::pair<const char*, double Run::*>, N>& figures) {
  if (runs.size() < 2) return nullptr;
  nlohmann::json spread = nlohmann::json::object();
  for (const auto& [name, figure] : figures) {
    const Spread s = spread_of(runs, figure);
    spread[name] = {{"mean", s.mean}, {"sd", s.sd}, {"min", s.min}, {"max", s.max}};
  }
  return spread;
}

}  // namespace roving
