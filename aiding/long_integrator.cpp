#include "aiding/long_integrator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace deepnav::aiding {
namespace {

constexpr int kBitMs = 20;

/// a += s * b for the complex sums, with b's end state (timing, NCO, flags).
void add_scaled(CorrelatorEpoch& a, const CorrelatorEpoch& b, double s) {
  a.early += s * b.early;
  a.prompt += s * b.prompt;
  a.late += s * b.late;
  a.very_early += s * b.very_early;
  a.very_late += s * b.very_late;
  a.noise += b.noise;  // independent noise: its power adds whatever the sign
  a.noise_samples += b.noise_samples;
  a.samples += b.samples;
  a.integration_s += b.integration_s;
  a.code_period = b.code_period;
  a.code_phase_chips = b.code_phase_chips;
  a.carrier_phase_cycles = b.carrier_phase_cycles;
  a.carrier_doppler_hz = b.carrier_doppler_hz;
  a.code_rate_cps = b.code_rate_cps;
  a.cn0_dbhz = b.cn0_dbhz;
  a.pll_lock = b.pll_lock;
  a.code_lock = b.code_lock;
  a.bit_synced = b.bit_synced;
}

CorrelatorEpoch scaled(const CorrelatorEpoch& e, double s) {
  CorrelatorEpoch c = e;
  c.early *= s;
  c.prompt *= s;
  c.late *= s;
  c.very_early *= s;
  c.very_late *= s;
  return c;
}

}  // namespace

IntegrationPower power_of(const CorrelatorEpoch& e, double fs) {
  return coherent_power(e.prompt, e.noise, static_cast<double>(e.first_sample + e.samples) / fs, e.integration_s,
                        e.noise_samples / fs);
}

IntegrationPower power_of(const SteeredIntegration& s, double fs) {
  IntegrationPower p = power_of(s.sums, fs);
  p.noise_power = s.noise_power;
  p.noise_s = s.noise_samples / fs;
  if (s.data_wiped) {
    p.data_wiped = true;
    p.wiped_prompt = s.sums.prompt;
  } else {
    p.prompt_power = s.prompt_power;
    p.sum_t_s = s.pieces * s.piece_s;
    p.sum_t2_s2 = s.pieces * s.piece_s * s.piece_s;
  }
  return p;
}

void validate(const LongIntegrationConfig& c) {
  const auto check = [](int ms, const char* name) {
    if (ms < kBitMs || ms % kBitMs != 0)
      throw std::invalid_argument(std::string("long integration: ") + name +
                                  " must be a positive multiple of 20 ms, got " + std::to_string(ms));
  };
  check(c.coherent_ms, "coherent_ms");
  check(c.noncoherent_ms, "noncoherent_ms");
  if (!(c.leave_above_dbhz >= c.enter_below_dbhz))
    throw std::invalid_argument("long integration: leave_above_dbhz must not be below enter_below_dbhz");
}

LongIntegrator::LongIntegrator(const LongIntegrationConfig& config) : cfg_(config) { validate(cfg_); }

void LongIntegrator::reset() {
  bit_.reset();
  bit_ms_ = 0;
  run_.reset();
  run_ms_ = 0;
  end_sample_ = -1;
  last_wiped_prompt_.reset();
}

std::optional<std::complex<double>> LongIntegrator::phase_reference() const {
  if (run_) {
    if (run_->data_wiped) return run_->sums.prompt;
    return std::nullopt;
  }
  return last_wiped_prompt_;
}

void LongIntegrator::add(const CorrelatorEpoch& e, std::int64_t bit_edge_period, const BitSigner& signer,
                         std::vector<SteeredIntegration>& out) {
  if (end_sample_ >= 0 && e.first_sample != end_sample_) reset();  // samples were skipped
  end_sample_ = e.first_sample + e.samples;
  const int ms = static_cast<int>(std::lround(e.integration_s * 1000.0));
  const auto bit_phase = [&](std::int64_t p) { return code_periods_into_bit(p, bit_edge_period); };
  const std::int64_t start = e.code_period - ms;
  if (bit_phase(start) == 0) {
    // The NCO phase where the bit began (a phase correction inside its first integration
    // is not separated out: it is a small fraction of a cycle).
    bit_start_phase_cycles_ = e.carrier_phase_cycles - e.integration_s * e.carrier_doppler_hz;
    bit_ = e;
    bit_ms_ = ms;
    bit_start_period_ = start;
    bit_noise_power_ = std::norm(e.noise);
  } else if (bit_) {
    add_scaled(*bit_, e, 1.0);
    bit_ms_ += ms;
    bit_noise_power_ += std::norm(e.noise);
  }
  if (!bit_ || bit_phase(e.code_period) != 0) return;
  if (bit_ms_ == kBitMs) finish_bit(signer, out);
  bit_.reset();
  bit_ms_ = 0;
}

void LongIntegrator::finish_bit(const BitSigner& signer, std::vector<SteeredIntegration>& out) {
  const int sign = signer(bit_start_period_, bit_->prompt);
  const bool wiped = sign != 0 && cfg_.coherent_ms > kBitMs;
  // A run holds one kind of integration only.
  if (run_ && run_->data_wiped != wiped) flush(out);
  if (!run_) {
    run_.emplace();
    run_->start_carrier_phase_cycles = bit_start_phase_cycles_;
    run_->sums = wiped ? scaled(*bit_, sign) : *bit_;
    run_->data_wiped = wiped;
    run_->pieces = 0;
    run_->piece_s = wiped ? 0.0 : bit_->integration_s;
    run_ms_ = 0;
  } else if (wiped) {
    add_scaled(run_->sums, *bit_, sign);
  } else {
    const std::complex<double> pair = std::conj(run_->sums.prompt) * bit_->prompt;
    run_->frequency_product += pair.real() < 0.0 ? -pair : pair;
    ++run_->frequency_pairs;
    CorrelatorEpoch last = *bit_;
    last.first_sample = run_->sums.first_sample;
    last.samples += run_->sums.samples;
    last.integration_s += run_->sums.integration_s;
    last.noise += run_->sums.noise;  // the noise reference keeps every piece
    last.noise_samples += run_->sums.noise_samples;
    run_->sums = last;
  }
  run_->noise_power += bit_noise_power_;
  run_->noise_samples += bit_->noise_samples;
  if (!wiped) {
    ++run_->pieces;
    run_->early_power += std::norm(bit_->early);
    run_->prompt_power += std::norm(bit_->prompt);
    run_->late_power += std::norm(bit_->late);
  }
  run_ms_ += kBitMs;
  if (run_ms_ >= (wiped ? cfg_.coherent_ms : cfg_.noncoherent_ms)) flush(out);
}

void LongIntegrator::flush(std::vector<SteeredIntegration>& out) {
  if (!run_) return;
  if (run_->data_wiped) {
    run_->pieces = 1;
    run_->piece_s = run_->sums.integration_s;
    run_->early_power = std::norm(run_->sums.early);
    run_->prompt_power = std::norm(run_->sums.prompt);
    run_->late_power = std::norm(run_->sums.late);
  }
  if (run_->data_wiped) last_wiped_prompt_ = run_->sums.prompt;
  else last_wiped_prompt_.reset();
  out.push_back(*run_);
  run_.reset();
  run_ms_ = 0;
}

}  // namespace deepnav::aiding
