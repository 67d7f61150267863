#include "receiver/navdata/ephemeris_words.hpp"

#include <algorithm>

namespace deepnav {
namespace {

constexpr std::int64_t kSubframesPerFrame = 5;
/// Frames kept: enough to combine the words of a start's partial frame with the next one's.
constexpr std::size_t kFramesKept = 4;

}  // namespace

EphemerisWords::EphemerisWords(int prn, int reference_week) : prn_(prn), reference_week_(reference_week) {}

bool EphemerisWords::add(std::int64_t subframe_of_week, int word_index, std::uint32_t data24) {
  const int subframe_id = lnav::subframe_id_at(subframe_of_week);
  if (subframe_id > 3 || word_index < 0 || word_index > 9) return false;
  const std::int64_t frame_count = subframe_of_week / kSubframesPerFrame;
  // Frame counts restart with the week: what came before the rollover cannot be combined.
  if (!frames_.empty() && frame_count < frames_.rbegin()->first) frames_.clear();
  Frame& frame = frames_[frame_count];
  frame.words[static_cast<std::size_t>(subframe_id - 1)][static_cast<std::size_t>(word_index)] = data24;
  if (const auto iod = lnav::issue_of_data_in_word(subframe_id, word_index, data24)) {
    if (frame.issue_of_data && *frame.issue_of_data != *iod) frame.conflicting = true;
    frame.issue_of_data = *iod;
  }
  while (frames_.size() > kFramesKept) frames_.erase(frames_.begin());
  if (!frame.issue_of_data || frame.conflicting) return false;
  const auto e = assemble(*frame.issue_of_data);
  if (!e) return false;
  const bool changed = !ephemeris_ || ephemeris_->iode != e->iode || ephemeris_->iodc != e->iodc ||
                       ephemeris_->toe_s != e->toe_s || ephemeris_->week != e->week || ephemeris_->health != e->health;
  ephemeris_ = e;
  return changed;
}

std::optional<Ephemeris> EphemerisWords::assemble(int iod) const {
  lnav::EphemerisAssembler assembler(prn_, reference_week_);
  // Single words serve the first ephemeris, when every second counts. After it, a word that
  // noise let through parity (one in 64) would replace a good one; so updates take whole
  // copies, all ten words of a subframe, as broadcast data sets change at most every hour.
  const bool whole_copies_only = ephemeris_.has_value();
  for (int id = 1; id <= 3; ++id) {
    // Each word from the newest frame of this issue of data that has it.
    lnav::PartialSubframeData merged;
    std::optional<std::int64_t> last_word_frame;
    for (auto it = frames_.rbegin(); it != frames_.rend(); ++it) {
      const Frame& f = it->second;
      if (f.conflicting || f.issue_of_data != iod) continue;
      const auto& words = f.words[static_cast<std::size_t>(id - 1)];
      if (whole_copies_only && !std::all_of(words.begin(), words.end(), [](const auto& w) { return w.has_value(); }))
        continue;
      for (std::size_t w = 0; w < merged.size(); ++w)
        if (!merged[w] && words[w]) merged[w] = words[w];
      if (!last_word_frame && words[9]) last_word_frame = it->first;
    }
    // The subframe's HOW count as in the copy its last word came from (subframe 1: the
    // ephemeris's transmission time).
    const std::int64_t frame = last_word_frame.value_or(frames_.rbegin()->first);
    const auto tow_count = static_cast<int>((frame * kSubframesPerFrame + id) % lnav::kTowCountsPerWeek);
    const auto sf = lnav::decode_partial_subframe(id, tow_count, merged);
    if (!sf) return std::nullopt;
    assembler.add(*sf);
  }
  return assembler.ephemeris();
}

}  // namespace deepnav
