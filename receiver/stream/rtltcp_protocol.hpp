#pragma once
// The rtl_tcp protocol (rtl-sdr's network server for RTL2832U dongles). On connecting, the
// server sends 12 bytes: the magic "RTL0", the tuner type and the number of gain steps of
// the tuner (both big-endian u32); then unsigned 8-bit I/Q samples (cu8) without end or
// framing. The client tunes the dongle with 5-byte commands: a command byte and a
// big-endian u32 parameter. Here: the header, the commands and the tuning a GPS L1 receiver
// sends.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace deepnav::rtltcp {

inline constexpr std::size_t kDongleInfoBytes = 12;
inline constexpr std::size_t kCommandBytes = 5;

/// Command bytes of rtl_tcp (those this client sends, and the ones next to them).
enum class Command : std::uint8_t {
  set_frequency = 0x01,        ///< centre frequency, Hz
  set_sample_rate = 0x02,      ///< samples/s
  set_gain_mode = 0x03,        ///< 0: tuner AGC (automatic gain), 1: manual gain
  set_gain = 0x04,             ///< tuner gain, tenths of a dB (the nearest step is taken)
  set_freq_correction = 0x05,  ///< crystal correction, ppm (signed)
  set_if_gain = 0x06,
  set_test_mode = 0x07,
  set_agc_mode = 0x08,  ///< RTL2832 digital AGC: 0 off, 1 on
  set_direct_sampling = 0x09,
  set_offset_tuning = 0x0a,
  set_rtl_crystal = 0x0b,
  set_tuner_crystal = 0x0c,
  set_gain_by_index = 0x0d,
  set_bias_tee = 0x0e,  ///< 0 off, 1: power on the antenna input (active antennas)
};

struct DongleInfo {
  std::uint32_t tuner_type = 0;  ///< 1 E4000, 2 FC0012, 3 FC0013, 4 FC2580, 5 R820T, 6 R828D
  std::uint32_t gain_count = 0;  ///< gain steps the tuner has
};

/// Throws stream::ProtocolError (stream_protocol.hpp) naming the field for a wrong magic.
DongleInfo decode_dongle_info(std::span<const std::byte, kDongleInfoBytes> bytes);
std::array<std::byte, kDongleInfoBytes> encode(const DongleInfo& info);
/// The tuner's name ("R820T", ...; "unknown tuner N" otherwise).
std::string tuner_name(std::uint32_t tuner_type);

std::array<std::byte, kCommandBytes> encode_command(Command command, std::uint32_t parameter);

/// What the client asks of the dongle.
struct Tuning {
  double center_frequency_hz = 1575.42e6;
  std::uint32_t sample_rate_hz = 2048000;
  std::optional<double> gain_db;  ///< manual tuner gain; none: the tuner's own AGC
  bool rtl_agc = false;           ///< the RTL2832's digital AGC
  int ppm = 0;                    ///< crystal correction
  bool bias_tee = false;          ///< power an active antenna through the coax
};

/// Throws std::invalid_argument naming the setting (frequency outside the R820T's 24 MHz to
/// 1.766 GHz, a sample rate the RTL2832 does not make (225-300 kHz or 900 kHz-3.2 MHz),
/// gain outside 0..60 dB, ppm beyond +-1000).
void validate(const Tuning& tuning);

/// The commands, in order: sample rate, centre frequency, crystal correction, gain mode
/// (and the gain when manual), digital AGC, bias tee.
std::vector<std::array<std::byte, kCommandBytes>> tuning_commands(const Tuning& tuning);

}  // namespace deepnav::rtltcp
