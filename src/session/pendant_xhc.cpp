// The XHC WHB04B pendant's reports as pendant events, and its display.
#include "gantry/session/pendant_xhc.hpp"

#include <algorithm>
#include <cmath>

namespace gantry::session {
namespace {

using pendant::XhcKey;

// A key's button, and its macro with Fn (the number printed beside it); 0: none.
struct KeyMeaning {
  std::optional<PendantButton> button;
  int fn_macro = 0;
};

KeyMeaning meaning(XhcKey k) {
  switch (k) {
    case XhcKey::Reset: return {PendantButton::Reset, 0};
    case XhcKey::Stop: return {PendantButton::Stop, 0};
    case XhcKey::StartPause: return {PendantButton::StartPause, 0};
    case XhcKey::FeedPlus: return {PendantButton::FeedPlus, 1};
    case XhcKey::FeedMinus: return {PendantButton::FeedMinus, 2};
    case XhcKey::SpindlePlus: return {PendantButton::SpindlePlus, 3};
    case XhcKey::SpindleMinus: return {PendantButton::SpindleMinus, 4};
    case XhcKey::MachineHome: return {PendantButton::MachineHome, 5};
    case XhcKey::SafeZ: return {PendantButton::SafeZ, 6};
    case XhcKey::WorkHome: return {PendantButton::WorkHome, 7};
    case XhcKey::SpindleOnOff: return {PendantButton::SpindleOnOff, 8};
    case XhcKey::ProbeZ: return {PendantButton::ProbeZ, 9};
    case XhcKey::Macro10: return {PendantButton::Macro, 10};
    default: return {};
  }
}

}  // namespace

void XhcTranslator::reset() {
  held1_ = held2_ = XhcKey::None;
}

std::vector<PendantEvent> XhcTranslator::events(const pendant::XhcReport& r) {
  std::vector<PendantEvent> out;
  if (r.asleep()) {
    reset();
    out.push_back({.kind = PendantEvent::Kind::Lost});
    return out;
  }
  axis_ = pendant::knob_axis(r.axis_knob);
  const bool fn = r.key1 == XhcKey::Fn || r.key2 == XhcKey::Fn;
  for (XhcKey k : {r.key1, r.key2}) {
    if (k == XhcKey::None || k == XhcKey::Fn || k == held1_ || k == held2_) continue;  // held
    if (k == XhcKey::Continuous || k == XhcKey::Step) {
      step_mode_ = k == XhcKey::Step;
      continue;
    }
    if (k == XhcKey::Macro10 && !fn) {  // the display's frame: work or machine coordinates
      machine_ = !machine_;
      continue;
    }
    const KeyMeaning m = meaning(k);
    if (!m.button) continue;
    PendantEvent e{.kind = PendantEvent::Kind::Button, .button = *m.button};
    // Reset, stop and start/pause stay themselves with Fn: a stop is never a macro.
    if (k == XhcKey::Macro10 || (fn && m.fn_macro > 0)) {
      e.button = PendantButton::Macro;
      e.macro = m.fn_macro;
    }
    out.push_back(e);
  }
  held1_ = r.key1;
  held2_ = r.key2;
  const pendant::FeedKnob knob = pendant::feed_knob(r.feed_knob);
  if (r.delta != 0 && knob.lead) {  // Lead: the wheel is the spindle's, whatever the axis knob
    out.push_back({.kind = PendantEvent::Kind::Lead, .delta = r.delta});
    return out;
  }
  if (r.delta != 0 && axis_ >= 0) {
    PendantEvent e{.kind = PendantEvent::Kind::Wheel, .axis = axis_, .delta = r.delta};
    if (step_mode_) {
      e.step = knob.step;  // 60 %, 100 %, Lead: no step size, no step
      if (e.step > 0) out.push_back(e);
    } else if (knob.percent > 0) {
      e.percent = knob.percent;
      out.push_back(e);
    }
  }
  return out;
}

pendant::XhcDisplay xhc_display(const ControllerStatus& s, const Vec6& at, bool step_mode,
                                int axis, bool machine) {
  pendant::XhcDisplay d;
  d.work_coordinates = !machine;
  d.mode = step_mode ? pendant::XhcDisplay::Mode::Step : pendant::XhcDisplay::Mode::Continuous;
  d.reset = s.state == MachineState::EStop;
  const int first = axis >= 3 ? 3 : 0;
  for (int i = 0; i < 3; ++i) d.coordinates[static_cast<std::size_t>(i)] = at[first + i];
  d.feed = static_cast<std::uint16_t>(std::lround(std::clamp(s.feed_override, 0.0, 6.0) * 100));
  d.spindle = static_cast<std::uint16_t>(std::lround(std::clamp(s.spindle_rpm, 0.0, 65535.0)));
  return d;
}

}  // namespace gantry::session
