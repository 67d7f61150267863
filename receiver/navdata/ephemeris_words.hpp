#pragma once
// A satellite's ephemeris from single LNAV words rather than whole subframes, so that a cold
// start uses every word it received: those of the subframes under way when the channel
// started, and words of different frames.
//
// Words of different frames belong to one data set when their frames' issue of data agree:
// the control segment changes the data set only at a frame boundary, so every word of
// subframes 1-3 in one frame belongs to the data set the frame's IODC (subframe 1 word 8,
// 8 LSBs) and IODE (subframe 2 word 3, subframe 3 word 10) name. A frame whose issue-of-data
// words disagree is not used; a frame none of whose issue-of-data words was received is not
// used either. The ephemeris is complete once one issue of data has, from such frames,
// subframe 1's clock words 7-10 and words 3-10 of subframes 2 and 3; subframe 1's word 3
// (week number, health, URA) is added where received (lnav::decode_partial_subframe).
// Later ephemerides (a new data set, subframe 1's word 3 arriving) take only whole copies of
// a subframe, all ten words passing parity, so that a word noise let through parity (one in
// 64) cannot replace a good one in the ephemeris in use.
#include <array>
#include <cstdint>
#include <map>
#include <optional>

#include "signals/ephemeris.hpp"
#include "signals/lnav_message.hpp"

namespace deepnav {

class EphemerisWords {
 public:
  /// `reference_week` resolves the broadcast 10-bit week number (and stands in for it until
  /// subframe 1's word 3 is received).
  EphemerisWords(int prn, int reference_week);

  /// Word `word_index` (0-based) of the subframe that starts at subframe count
  /// `subframe_of_week` (its HOW TOW count minus 1), its data d1..d24 with parity checked.
  /// Returns true when the ephemeris was completed or changed in a field the receiver uses
  /// to tell data sets apart (issue of data, toe, week, health).
  bool add(std::int64_t subframe_of_week, int word_index, std::uint32_t data24);

  const std::optional<Ephemeris>& ephemeris() const { return ephemeris_; }

 private:
  /// Words 1-10 of subframes 1-3 of one frame, and the issue of data they name.
  struct Frame {
    std::array<lnav::PartialSubframeData, 3> words{};
    std::optional<int> issue_of_data;
    bool conflicting = false;
  };
  /// The ephemeris of issue of data `iod` from the newest frames that name it, if complete.
  std::optional<Ephemeris> assemble(int iod) const;

  int prn_;
  int reference_week_;
  std::map<std::int64_t, Frame> frames_;  ///< by frame count of the week (subframe_of_week / 5)
  std::optional<Ephemeris> ephemeris_;
};

}  // namespace deepnav
