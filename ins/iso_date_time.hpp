#pragma once
// A date and time as people write them: "YYYY-MM-DDThh:mm:ss[.fff]" (a space may replace
// the T), optionally ending in "Z" (UTC). One reading for every text field and option that
// takes one (a scenario's start_time, a time hint), so that they accept the same forms.
#include <optional>
#include <string>

#include "ins/gps_time.hpp"

namespace deepnav {

struct IsoDateTime {
  CalendarTime calendar;  ///< the fields as written (not yet checked: is_valid_calendar)
  bool utc = false;       ///< the text ended in "Z"
};

/// The fields of `text`, or nullopt when it has another form (signs, missing fields,
/// trailing text, or a "Z" where `z_allowed` is false).
std::optional<IsoDateTime> parse_iso_date_time(const std::string& text, bool z_allowed);

}  // namespace deepnav
