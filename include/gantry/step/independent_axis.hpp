// One axis moving on its own beside the planned path (MI): its steps, in time order, for the
// step generator to merge with the path's.
#pragma once

#include <cstdint>
#include <optional>

#include "gantry/canon/canon_move.hpp"  // IndependentMotion

namespace gantry {

// Positions are in steps from the start count (a whole step), times in ticks from the start
// tick. As for the path, a step is due when the exact position crosses the half step before
// it, so the count is exact and every step is within half a tick of its ideal instant.
//
// Turning: u(t) = a t^2 / 2 up to the speed v (at t1 = v / a, u1 = v^2 / 2a), then
// u1 + v (t - t1). Asked to stop at ts, where it runs at vs having gone us, it slows at a:
// u = us + vs (t - ts) - a (t - ts)^2 / 2 up to ue = us + vs^2 / 2a. The k-th step crosses
// u = k - 1/2, so its time is the inverse of the piece it falls in (a square root or a line).
//
// Oscillating over D steps at w radians per tick: u(t) = D (1 - cos w t) / 2, from rest at
// the start point out to D and back once per cycle; speed peaks at D w / 2, acceleration at
// D w^2 / 2. In cycle m the crossing of u = k - 1/2 (k = 1..N, N the half steps below D)
// goes out at (2 pi m + th_k) / w and comes back at (2 pi (m + 1) - th_k) / w, with
// th_k = acos(1 - (2k - 1) / D). Asked to stop, it finishes the cycle it is in: back at its
// start count exactly, at rest.
class IndependentAxis {
 public:
  IndependentAxis(const IndependentMotion& m, double steps_per_unit, double tick_s,
                  std::int64_t start_tick);

  const IndependentMotion& motion() const { return motion_; }
  int axis() const { return motion_.axis; }
  struct Step {
    double tick;  // ideal, on the card's clock
    bool positive;
  };
  // The next step; nullopt once it has come to rest for good (after stop_from).
  std::optional<Step> next() const;
  void taken();  // the step next() gave went out
  // It comes to rest from `tick` on, as described above. Steps before it are taken already.
  void stop_from(std::int64_t tick);

 private:
  double crossing(int k) const;  // oscillating: th_k

  IndependentMotion motion_;
  std::int64_t t0_;
  bool turning_;
  bool positive_;  // turning: its direction; oscillating: the way out
  // Turning, in steps and ticks.
  double v_ = 0, a_ = 0;
  std::int64_t taken_ = 0;
  bool stopping_ = false;  // stop_from was called
  double ts_ = 0, vs_ = 0, us_ = 0, ue_ = 0;
  // Oscillating.
  double d_ = 0, w_ = 0;
  int n_ = 0;                    // steps out (and back) per cycle
  std::int64_t cycle_ = 0;       // m
  int in_cycle_ = 0;             // steps of this cycle taken: 0 .. 2n-1
  std::int64_t last_cycle_ = 0;  // stopping: the cycle it ends with
};

}  // namespace gantry
