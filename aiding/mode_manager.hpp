#pragma once
// Which coupling runs now. The user asks for one mode; when what that mode needs is
// missing (satellites, lock, a healthy and converged filter) the manager falls back along
// ultra -> tight -> loose -> coast (INS alone) -> scalar, and returns to the asked-for mode
// once it has been possible again for `return_after_s`. Falling back is immediate.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace deepnav::aiding {

enum class NavMode { scalar, coast, loose, tight, ultra };
const char* to_string(NavMode mode);
/// The mode of that name, coast included (nullopt: none).
std::optional<NavMode> nav_mode_named(std::string_view name);
/// Parses "scalar", "loose", "tight" or "ultra" (the modes a user can ask for); throws
/// std::invalid_argument naming the choices.
NavMode parse_nav_mode(const std::string& text);

/// What the modes need, as seen at one instant.
struct ModeInputs {
  bool ins_ready = false;  ///< the INS is initialised
  bool filter_healthy = false;
  bool recent_pvt = false;          ///< a valid receiver PVT within the last few seconds
  int ranging_satellites = 0;       ///< channels with ephemeris, transmit time and usable C/N0
  int steerable_channels = 0;       ///< channels an ultra-tight filter could take over
  double horizontal_sigma_m = 1e9;  ///< filter's 1-sigma horizontal position uncertainty
  double velocity_sigma_mps = 1e9;  ///< filter's 1-sigma velocity uncertainty (largest axis)
};

struct ModeLimits {
  double ultra_enter_sigma_m = 10.0;           ///< converged enough to take the channels over
  double ultra_keep_sigma_m = 40.0;            ///< 0.14 chip: beyond it predicted code phases are unsafe
  double ultra_keep_velocity_sigma_mps = 1.5;  ///< ~8 Hz of carrier: beyond it the FLL range is at risk
  double return_after_s = 2.0;
};

struct ModeChange {
  double t_s = 0.0;
  NavMode from = NavMode::scalar, to = NavMode::scalar;
  std::string reason;
};

class ModeManager {
 public:
  explicit ModeManager(NavMode requested, ModeLimits limits = {});
  /// The mode to run from time t on.
  NavMode update(double t_s, const ModeInputs& in);
  NavMode mode() const { return mode_; }
  NavMode requested() const { return requested_; }
  const std::vector<ModeChange>& changes() const { return changes_; }

 private:
  /// Empty when `mode` can run now, else why not.
  std::string missing(NavMode mode, const ModeInputs& in) const;
  NavMode requested_;
  ModeLimits limits_;
  NavMode mode_ = NavMode::scalar;
  NavMode better_candidate_ = NavMode::scalar;
  double better_since_s_ = 0.0;
  std::vector<ModeChange> changes_;
};

}  // namespace deepnav::aiding
