// The pass model: how plunge, repetitions, spiral, bottom pass, pocket rings and tabs
// combine into one tool path (docs/cuts.md, "Passes").
#include "gantry/cuts/passes.hpp"

#include <algorithm>  // max, min
#include <cmath>      // ceil, floor

namespace gantry::cuts {

double PassPlan::clear_z() const {
  return plunge_negative ? std::max(safe_z, z_start) : std::min(safe_z, z_start);
}

double PassPlan::depth(int pass) const {
  return (from_zero ? 0.0 : z_start) + pass * plunge;
}

namespace {

// One series of tabs: the k-th starts at first + k * step, where step is the spacing, or the
// tab's own length when the spacing is shorter (the tabs then run end to end).
struct TabSeries {
  double first, span, step;
  int most;  // 0: no limit
  explicit TabSeries(const TabPlan& t)
      : first(t.first),
        span(2 * t.sizes.leads + t.sizes.size),
        step(std::max(t.sizes.spacing, span)),
        most(t.most) {}
  bool usable(const TabPlan& t) const { return t.on && span > 0 && step > 0; }
  double start(int k) const { return first + k * step; }
  bool allowed(int k) const { return most <= 0 || k < most; }
  // How many tabs end at or before s.
  int ended_by(double s) const {
    const double k = std::floor((s + 1e-9 - span - first) / step) + 1;
    const int n = k > 0 ? static_cast<int>(std::min(k, 1e9)) : 0;
    return most > 0 ? std::min(n, most) : n;
  }
};

// Tab k's profile: up over the leads, level for the size, down over the leads; distances
// measured from `origin`.
void add_tab(Profile& p, const TabSettings& z, double s, double lift, double origin) {
  const double a = s - origin;
  p.points.insert(p.points.end(), {{a, 0.0},
                                   {a + z.leads, lift},
                                   {a + z.leads + z.size, lift},
                                   {a + 2 * z.leads + z.size, 0.0}});
}

}  // namespace

Profile tab_profile(double length, const TabPlan& t, double lift, int* count) {
  Profile p = Profile::constant(0);
  int n = 0;
  const TabSeries series(t);
  if (series.usable(t))
    for (int k = 0; series.start(k) + series.span <= length + 1e-9 && series.allowed(k); ++k) {
      add_tab(p, t.sizes, series.start(k), lift, 0);
      ++n;
    }
  if (count) *count = n;
  return p;
}

Profile tab_window(const TabPlan& t, double lift, double from, double to, int* ended) {
  Profile p;
  const TabSeries series(t);
  int n = 0;
  if (series.usable(t)) {
    // The first tab that may still be under way at `from`.
    int k = std::max(
        0, static_cast<int>(std::floor((from - series.span - series.first) / series.step)));
    for (; series.allowed(k) && series.start(k) < to; ++k)
      if (series.start(k) + series.span > from) add_tab(p, t.sizes, series.start(k), lift, from);
    n = series.ended_by(to);
  }
  if (p.points.empty()) p = Profile::constant(0);
  if (ended) *ended = n;
  return p;
}

CutPath tab_stretch(const V3& tool, double lift_now, const Piece& piece, double z_to, double travel,
                    const TabPlan& t, double lift, int* ended) {
  PathBuilder b(tool);
  const double len = piece.length();
  const Profile z = Profile::ramp(len, tool.z() - lift_now, z_to) +
                    tab_window(t, lift, travel, travel + len, ended);
  b.follow({piece}, z);
  return b.take();
}

namespace {

V2 start_of(const Contour& c) {
  return c.front().from;
}

}  // namespace

CutPath run_passes(const V3& start, const std::vector<Contour>& rings, bool closed,
                   const PassPlan& plan) {
  PathBuilder b(start);
  const V2 home = start.head<2>();
  const double clear = plan.clear_z();
  const double up = plan.plunge_negative ? 1.0 : -1.0;
  const Contour& path = rings.front();
  const double total = length(path);
  if (plan.from_zero) b.z(0, Role::Plunge);
  const int passes = plan.repetitions + (plan.bottom_pass ? 1 : 0);
  for (int j = 0; j < passes; ++j) {
    const bool bottom = j >= plan.repetitions;
    const int k = bottom ? plan.repetitions : j + 1;
    const double z_from = plan.depth(bottom ? k : k - 1), z_to = plan.depth(k);
    const bool spiral = plan.spiral && !bottom;
    const bool last = j == passes - 1;
    if (j > 0 && !closed) {  // an open path: back to its start above the work
      b.z(clear, Role::Retract);
      b.xy(home, Role::Reposition);
    }
    if (plan.pocket == Pocket::OutsideIn) {
      b.z(z_to, Role::Plunge);
      for (const Contour& ring : rings) {
        b.xy(start_of(ring), Role::Cut);  // inward, across what the last ring cleared
        b.follow(ring, Profile::constant(z_to));
      }
      b.xy(home, Role::Cut);  // back out along the same line, at depth
      continue;
    }
    if (plan.pocket == Pocket::InsideOut) {
      // Across at the depth already cleared (the start Z for the first pass) to the centre.
      b.xy(start_of(rings.back()), Role::Cut);
      b.z(z_to, Role::Plunge);
      for (auto ring = rings.rbegin(); ring != rings.rend(); ++ring) {
        b.xy(start_of(*ring), Role::Cut);
        b.follow(*ring, Profile::constant(z_to));
      }
      continue;
    }
    b.z(spiral ? z_from : z_to, Role::Plunge);
    Profile z = spiral ? Profile::ramp(total, z_from, z_to) : Profile::constant(z_to);
    if (last && plan.tabs.on)
      z = z + tab_profile(total, plan.tabs, up * plan.tabs.sizes.pull_up, &b.path().tabs);
    b.follow(path, z);
  }
  // Back to the Z the command started at, and only if Z changed (FabMo's rule; docs/cuts.md
  // D9): a cut at the tool's depth ends there, ready for the next move of the profile. Up
  // out of the work at jog speed; down (the cut ended above its start) at move speed.
  if (plan.pull_up)
    b.z(plan.z_start, plan.is_up(b.at().z(), plan.z_start) ? Role::Retract : Role::Plunge);
  return b.take();
}

std::vector<double> pocket_scales(double reach, double step) {
  std::vector<double> k = {1.0};
  if (!(step > 0) || !(reach > step / 2)) return k;
  const double inner = (step / 2) / reach;
  const int n = static_cast<int>(std::ceil((reach - step / 2) / step - 1e-9));
  for (int i = 1; i <= n; ++i) k.push_back(1 - (1 - inner) * i / n);
  return k;
}

std::vector<double> pocket_insets(double w, double h, double step) {
  std::vector<double> d = {0.0};
  const double half = std::min(w, h) / 2;
  if (!(step > 0) || !(half > step / 2)) return d;
  const int n = static_cast<int>(std::ceil((half - step / 2) / step - 1e-9));
  for (int i = 1; i <= n; ++i) d.push_back((half - step / 2) * i / n);
  return d;
}

}  // namespace gantry::cuts
