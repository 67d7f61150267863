#include "receiver/stream/stream_sample_source.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace deepnav {
namespace {

constexpr std::size_t kMaxGapRecords = 10000;  // the count stays exact beyond it
constexpr auto kPollInterval = std::chrono::milliseconds(100);

}  // namespace

StreamSampleSource::StreamSampleSource(StreamSourceSettings settings, std::string url)
    : settings_(std::move(settings)), url_(std::move(url)), queue_(settings_.queue_bytes) {
  if (settings_.raw) {
    if (!(settings_.raw_sample_rate_hz > 0.0))
      throw std::invalid_argument(fmt::format("{}: a raw stream needs its sample rate (--fs)", url_));
    header_.format = settings_.raw_format;
    header_.sample_rate_hz = settings_.raw_sample_rate_hz;
    header_.if_hz = settings_.raw_if_hz;
    header_known_ = true;
    converter_.emplace(header_.format, settings_.inverted_spectrum);
  }
}

void StreamSampleSource::publish_header(const stream::StreamHeader& header) {
  std::lock_guard lock(header_mutex_);
  if (header_known_) return;
  header_ = header;
  header_known_ = true;
  header_changed_.notify_all();
}

void StreamSampleSource::start_io(std::function<void()> loop) {
  io_thread_ = std::thread(std::move(loop));
  if (settings_.raw) return;
  try {
    wait_for_header();
  } catch (...) {
    stop_io();
    throw;
  }
}

void StreamSampleSource::stop_io() {
  cancel_ = true;
  if (io_thread_.joinable()) io_thread_.join();
}

void StreamSampleSource::wait_for_header() {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(settings_.connect_timeout_s);
  std::unique_lock lock(header_mutex_);
  while (!header_known_) {
    if (stop_requested()) throw std::runtime_error(fmt::format("{}: interrupted before the stream started", url_));
    if (std::chrono::steady_clock::now() >= deadline)
      throw std::runtime_error(fmt::format("{}: no stream header within {} s", url_, settings_.connect_timeout_s));
    header_changed_.wait_for(lock, kPollInterval);
    if (!header_known_) {
      // The I/O thread may have given up (refused connection, protocol error).
      StreamPiece ignored;
      lock.unlock();
      const bool over = queue_.pop(ignored, std::chrono::milliseconds(0)) == StreamSampleQueue::PopResult::end;
      lock.lock();
      if (over && !header_known_) throw std::runtime_error(fmt::format("{}: {}", url_, queue_.end().reason));
    }
  }
  next_index_ = header_.start_sample_index;
  if (!converter_) converter_.emplace(header_.format, settings_.inverted_spectrum != header_.inverted_spectrum);
}

StreamStats StreamSampleSource::stats() const {
  std::lock_guard lock(stats_mutex_);
  return stats_;
}

bool StreamSampleSource::next_piece() {
  while (held_.empty()) {
    if (ended_) return false;
    if (stop_requested()) {
      interrupted_ = true;
      cancel_ = true;
      update_stats([](StreamStats& s) {
        s.interrupted = true;
        s.end_reason = "interrupted";
      });
      return false;
    }
    StreamPiece piece;
    switch (queue_.pop(piece, kPollInterval)) {
      case StreamSampleQueue::PopResult::piece:
        if (!piece.raw.empty()) held_.push_back(std::move(piece));
        break;
      case StreamSampleQueue::PopResult::timeout:
        break;
      case StreamSampleQueue::PopResult::end: {
        ended_ = true;
        const StreamEnd end = queue_.end();
        end_index_ = end.end_sample_index;
        // A stream that ends before its first sample gave the run nothing to process: a
        // failure, not an empty run that looks like a finished one.
        const bool empty = delivered_ == 0;
        update_stats([&](StreamStats& s) {
          s.end_reason = empty && !end.failed ? fmt::format(
                                                    "the stream ended ({}) without a sample to process "
                                                    "({} bytes received)",
                                                    end.reason, s.bytes_received)
                                              : end.reason;
          s.failed = end.failed || empty;
        });
        return false;
      }
    }
  }
  return true;
}

void StreamSampleSource::calibrate_if_needed() {
  if (!converter_->needs_calibration()) return;
  // Hold the first kCalibrationSamples (or all there is) before converting any sample.
  const std::size_t wanted = SampleConverter::kCalibrationSamples * bytes_per_sample(header_.format);
  std::size_t have = 0;
  for (const auto& p : held_) have += p.raw.size();
  while (have < wanted && !ended_ && !stop_requested()) {
    StreamPiece piece;
    const auto r = queue_.pop(piece, kPollInterval);
    if (r == StreamSampleQueue::PopResult::piece) {
      have += piece.raw.size();
      held_.push_back(std::move(piece));
    } else if (r == StreamSampleQueue::PopResult::end) {
      break;  // next_piece() records the end
    }
  }
  std::vector<std::byte> first;
  for (const auto& p : held_) {
    first.insert(first.end(), p.raw.begin(), p.raw.end());
    if (first.size() >= wanted) break;
  }
  converter_->calibrate(first);
}

std::size_t StreamSampleSource::read(std::span<Sample> out) {
  if (at_end_ || out.empty()) return 0;
  calibrate_if_needed();
  const std::size_t bps = bytes_per_sample(header_.format);
  std::size_t filled = 0;
  while (filled < out.size() && next_piece()) {
    StreamPiece& p = held_.front();
    const std::int64_t piece_index = p.first_sample_index + static_cast<std::int64_t>(held_offset_ / bps);
    const std::size_t left = (p.raw.size() - held_offset_) / bps;
    if (piece_index > next_index_) {
      if (filled > 0) break;  // the samples of one read never span a gap
      const SampleGap gap{next_index_, piece_index - next_index_};
      update_stats([&](StreamStats& s) {
        if (s.gaps.size() < kMaxGapRecords) s.gaps.push_back(gap);
      });
      report_gap(gap);
      next_index_ = piece_index;
    } else if (piece_index < next_index_) {
      // Sent again after a resume: those samples were delivered already.
      const auto skip =
          static_cast<std::size_t>(std::min<std::int64_t>(next_index_ - piece_index, static_cast<std::int64_t>(left)));
      held_offset_ += skip * bps;
      update_stats([&](StreamStats& s) { s.samples_duplicated += static_cast<std::int64_t>(skip); });
    } else {
      const std::size_t n = std::min(left, out.size() - filled);
      converter_->convert(std::span<const std::byte>(p.raw).subspan(held_offset_, n * bps), out.subspan(filled, n),
                          next_index_);
      held_offset_ += n * bps;
      filled += n;
      next_index_ += static_cast<std::int64_t>(n);
      delivered_ += static_cast<std::int64_t>(n);
    }
    if (held_offset_ >= p.raw.size()) {
      held_.pop_front();
      held_offset_ = 0;
    }
  }
  if (filled == 0 && end_index_ && *end_index_ > next_index_) {
    // Frames lost at the very end: no later piece shows their hole, the end frame does.
    const SampleGap gap{next_index_, *end_index_ - next_index_};
    update_stats([&](StreamStats& s) {
      if (s.gaps.size() < kMaxGapRecords) s.gaps.push_back(gap);
    });
    report_gap(gap);
    next_index_ = *end_index_;
  }
  if (filled == 0) at_end_ = true;
  return filled;
}

}  // namespace deepnav
