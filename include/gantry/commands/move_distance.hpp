// MD's angle: the ShopBot heading, in degrees clockwise from +Y (as a clock face seen from the
// front of the tool: 0 is 12 o'clock, 90 is 3 o'clock, +X).
#pragma once

#include <optional>
#include <string_view>

namespace gantry {

// The heading `text` names: absolute degrees ("90"), degrees right (clockwise) or left of
// `last` ("30R", "45L"; without a last move the R/L is ignored, as SB3 says), a clock time
// ("3:00" is 90, "1:30" is 45), or a compass point of up to three letters ("E" is 90, "SSW"
// is 202.5). nullopt when it is none of these.
std::optional<double> md_heading(std::string_view text, std::optional<double> last);

}  // namespace gantry
