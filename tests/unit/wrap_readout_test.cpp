// The console's and the window's readout: a rotary axis with axes.<axis>.wrap is shown
// modulo it, the exact position kept.
#include <gtest/gtest.h>

#include "gantry/session/live_position.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

TEST(WrapReadout, ARotaryAxisWithAWrapIsShownModuloItAndTheExactPositionKept) {
  Settings s = default_settings();
  s.axes[3].wrap = 360;
  ModalState m;
  m.position[3] = 450;
  m.position[0] = 450;  // X has no wrap
  session::LivePosition live;
  live.snapshot(m, s);
  const Vec6 shown = live.at(ControllerStatus{}, true);
  EXPECT_DOUBLE_EQ(shown[3], 90);
  EXPECT_DOUBLE_EQ(shown[0], 450);
  EXPECT_DOUBLE_EQ(live.exact()[3], 450);
}

}  // namespace
}  // namespace gantry
