#include "aiding/mode_manager.hpp"

#include <array>
#include <stdexcept>

namespace deepnav::aiding {
namespace {

/// The fallback chain, best first.
constexpr std::array<NavMode, 5> kChain{NavMode::ultra, NavMode::tight, NavMode::loose, NavMode::coast,
                                        NavMode::scalar};

int rank(NavMode m) {
  for (std::size_t i = 0; i < kChain.size(); ++i)
    if (kChain[i] == m) return static_cast<int>(i);
  return static_cast<int>(kChain.size());
}

}  // namespace

const char* to_string(NavMode mode) {
  switch (mode) {
    case NavMode::scalar:
      return "scalar";
    case NavMode::coast:
      return "coast";
    case NavMode::loose:
      return "loose";
    case NavMode::tight:
      return "tight";
    case NavMode::ultra:
      return "ultra";
  }
  return "?";
}

std::optional<NavMode> nav_mode_named(std::string_view name) {
  for (NavMode m : kChain)
    if (name == to_string(m)) return m;
  return std::nullopt;
}

NavMode parse_nav_mode(const std::string& text) {
  if (const auto m = nav_mode_named(text); m && *m != NavMode::coast) return *m;
  throw std::invalid_argument("unknown mode '" + text + "' (expected scalar, loose, tight or ultra)");
}

ModeManager::ModeManager(NavMode requested, ModeLimits limits) : requested_(requested), limits_(limits) {}

std::string ModeManager::missing(NavMode mode, const ModeInputs& in) const {
  if (mode == NavMode::scalar) return {};
  if (!in.ins_ready) return "INS not initialised";
  if (!in.filter_healthy) return "filter unhealthy";
  switch (mode) {
    case NavMode::coast:
      return {};
    case NavMode::loose:
      return in.recent_pvt ? std::string{} : "no receiver PVT";
    case NavMode::tight:
      return in.ranging_satellites >= 1 ? std::string{} : "no satellite with a usable pseudorange";
    case NavMode::ultra: {
      if (in.steerable_channels < 1) return "no channel to steer";
      const double limit = mode_ == NavMode::ultra ? limits_.ultra_keep_sigma_m : limits_.ultra_enter_sigma_m;
      if (in.horizontal_sigma_m > limit) return "position uncertainty too large to steer the channels";
      if (in.velocity_sigma_mps > limits_.ultra_keep_velocity_sigma_mps)
        return "velocity uncertainty too large to steer the carrier";
      return {};
    }
    default:
      return {};
  }
}

NavMode ModeManager::update(double t_s, const ModeInputs& in) {
  // The best mode possible now, starting from the one asked for.
  NavMode best = NavMode::scalar;
  for (std::size_t i = static_cast<std::size_t>(rank(requested_)); i < kChain.size(); ++i) {
    if (missing(kChain[i], in).empty()) {
      best = kChain[i];
      break;
    }
  }
  NavMode next = mode_;
  std::string reason;
  if (rank(best) > rank(mode_)) {
    next = best;  // the current mode cannot run: fall back at once
    reason = missing(mode_, in);
  } else if (rank(best) < rank(mode_)) {
    if (best != better_candidate_) {
      better_candidate_ = best;
      better_since_s_ = t_s;
    }
    // Returning to the INS/filter modes from scalar needs no wait (nothing to go back on).
    if (mode_ == NavMode::scalar || t_s - better_since_s_ >= limits_.return_after_s) {
      next = best;
      reason = best == requested_ ? "requested mode available" : "better mode available";
    }
  } else {
    better_candidate_ = mode_;
  }
  if (next != mode_) {
    changes_.push_back(ModeChange{t_s, mode_, next, reason});
    mode_ = next;
    better_candidate_ = next;
  }
  return mode_;
}

}  // namespace deepnav::aiding
