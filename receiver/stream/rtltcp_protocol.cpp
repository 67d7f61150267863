#include "receiver/stream/rtltcp_protocol.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "receiver/stream/stream_protocol.hpp"

namespace deepnav::rtltcp {
namespace {

std::uint32_t big_endian_u32(const std::byte* at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | std::to_integer<std::uint32_t>(at[i]);
  return v;
}

void put_big_endian_u32(std::byte* at, std::uint32_t v) {
  for (int i = 3; i >= 0; --i) {
    at[i] = static_cast<std::byte>(v & 0xFFu);
    v >>= 8;
  }
}

}  // namespace

DongleInfo decode_dongle_info(std::span<const std::byte, kDongleInfoBytes> bytes) {
  if (std::memcmp(bytes.data(), "RTL0", 4) != 0) {
    std::string seen;
    for (int i = 0; i < 4; ++i) {
      const auto c = std::to_integer<unsigned char>(bytes[static_cast<std::size_t>(i)]);
      seen += (c >= 0x20 && c < 0x7F) ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
    }
    throw stream::ProtocolError(
        fmt::format("rtl_tcp dongle header: magic is \"{}\", expected \"RTL0\" (is this an rtl_tcp server?)", seen));
  }
  return {big_endian_u32(bytes.data() + 4), big_endian_u32(bytes.data() + 8)};
}

std::array<std::byte, kDongleInfoBytes> encode(const DongleInfo& info) {
  std::array<std::byte, kDongleInfoBytes> b{};
  std::memcpy(b.data(), "RTL0", 4);
  put_big_endian_u32(b.data() + 4, info.tuner_type);
  put_big_endian_u32(b.data() + 8, info.gain_count);
  return b;
}

std::string tuner_name(std::uint32_t tuner_type) {
  switch (tuner_type) {
    case 1:
      return "E4000";
    case 2:
      return "FC0012";
    case 3:
      return "FC0013";
    case 4:
      return "FC2580";
    case 5:
      return "R820T";
    case 6:
      return "R828D";
  }
  return fmt::format("unknown tuner {}", tuner_type);
}

std::array<std::byte, kCommandBytes> encode_command(Command command, std::uint32_t parameter) {
  std::array<std::byte, kCommandBytes> b{};
  b[0] = static_cast<std::byte>(command);
  put_big_endian_u32(b.data() + 1, parameter);
  return b;
}

void validate(const Tuning& t) {
  if (!(t.center_frequency_hz >= 24e6 && t.center_frequency_hz <= 1766e6))
    throw std::invalid_argument(
        fmt::format("rtl_tcp centre frequency {} Hz is outside the tuner's 24 MHz to 1766 MHz", t.center_frequency_hz));
  const double fs = t.sample_rate_hz;
  if (!((fs > 225001 && fs <= 300000) || (fs > 900001 && fs <= 3200000)))
    throw std::invalid_argument(fmt::format(
        "rtl_tcp sample rate {} Hz is not one the RTL2832 makes (225-300 kHz or 900 kHz-3.2 MHz; 2.048 MHz is the "
        "usual choice, above 2.4 MHz samples get lost)",
        t.sample_rate_hz));
  if (t.gain_db && !(*t.gain_db >= 0.0 && *t.gain_db <= 60.0))
    throw std::invalid_argument(fmt::format("rtl_tcp gain {} dB is outside 0..60 dB", *t.gain_db));
  if (std::abs(t.ppm) > 1000)
    throw std::invalid_argument(fmt::format("rtl_tcp frequency correction {} ppm is beyond +-1000 ppm", t.ppm));
}

std::vector<std::array<std::byte, kCommandBytes>> tuning_commands(const Tuning& t) {
  std::vector<std::array<std::byte, kCommandBytes>> out;
  out.push_back(encode_command(Command::set_sample_rate, t.sample_rate_hz));
  out.push_back(
      encode_command(Command::set_frequency, static_cast<std::uint32_t>(std::llround(t.center_frequency_hz))));
  out.push_back(encode_command(Command::set_freq_correction, static_cast<std::uint32_t>(t.ppm)));  // two's complement
  out.push_back(encode_command(Command::set_gain_mode, t.gain_db ? 1u : 0u));
  if (t.gain_db)
    out.push_back(encode_command(Command::set_gain, static_cast<std::uint32_t>(std::lround(*t.gain_db * 10.0))));
  out.push_back(encode_command(Command::set_agc_mode, t.rtl_agc ? 1u : 0u));
  out.push_back(encode_command(Command::set_bias_tee, t.bias_tee ? 1u : 0u));
  return out;
}

}  // namespace deepnav::rtltcp
