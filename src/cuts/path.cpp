// Contours, Z profiles and the moves built from them.
#include "gantry/cuts/path.hpp"

#include <algorithm>  // sort, unique
#include <cmath>      // atan2, cos, sin, floor

namespace gantry::cuts {

double Piece::length() const {
  return arc ? radius() * std::abs(sweep) : (to - from).norm();
}

V2 Piece::at(double f) const {
  if (f <= 0) return from;
  if (f >= 1) return to;  // exactly: pieces join without drift
  if (!arc) return from + (to - from) * f;
  const double r = radius();
  const double a = std::atan2(from.y() - centre.y(), from.x() - centre.x()) + f * sweep;
  return centre + r * V2(std::cos(a), std::sin(a));
}

Piece Piece::part(double f0, double f1) const {
  Piece p = *this;
  p.from = at(f0);
  p.to = at(f1);
  p.sweep = sweep * (f1 - f0);
  return p;
}

double length(const Contour& c) {
  double s = 0;
  for (const Piece& p : c) s += p.length();
  return s;
}

double Profile::at(double s) const {
  if (points.empty()) return 0;
  if (s <= points.front().first) return points.front().second;
  if (s >= points.back().first) return points.back().second;
  const auto hi = std::upper_bound(points.begin(), points.end(), s,
                                   [](double v, const auto& p) { return v < p.first; });
  const auto lo = hi - 1;
  const double span = hi->first - lo->first;
  if (span <= 0) return hi->second;
  return lo->second + (hi->second - lo->second) * (s - lo->first) / span;
}

Profile operator+(const Profile& a, const Profile& b) {
  std::vector<double> s;
  for (const auto& p : a.points) s.push_back(p.first);
  for (const auto& p : b.points) s.push_back(p.first);
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  Profile out;
  for (double v : s) out.points.emplace_back(v, a.at(v) + b.at(v));
  return out;
}

void PathBuilder::line(const V3& to, Role role) {
  if ((to - at_).norm() < 1e-12) return;
  CutMove m;
  m.to = to;
  m.role = role;
  path_.moves.push_back(m);
  at_ = to;
}

// Walks the contour from one event to the next: the profile's breakpoints (in their order,
// so two at the same distance make a vertical step) and the ends of the pieces. Z is linear
// between events, so each move is a line or a helix whose Z is exact at both ends.
void PathBuilder::follow(const Contour& c, const Profile& z) {
  constexpr double kTiny = 1e-9;  // shorter than this is the same place
  std::vector<Piece> pieces;
  std::vector<double> ends;
  double total = 0;
  for (const Piece& p : c)
    if (p.length() >= kTiny) {
      pieces.push_back(p);
      total += p.length();
      ends.push_back(total);
    }
  struct Event {
    double s, z;
  };
  std::vector<Event> events;
  for (const auto& bp : z.points)
    if (bp.first >= -kTiny && bp.first <= total + kTiny)
      events.push_back({std::clamp(bp.first, 0.0, total), bp.second});
  for (double e : ends) {
    const bool covered = std::any_of(z.points.begin(), z.points.end(), [&](const auto& bp) {
      return std::abs(bp.first - e) <= kTiny;
    });
    if (!covered) events.push_back({e, z.at(e)});
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.s < b.s; });
  size_t i = 0;
  double s = 0, piece_start = 0;
  for (const Event& ev : events) {
    while (i < pieces.size() && ev.s > ends[i] + kTiny) {  // not expected: ends are events
      piece_start = ends[i++];
      s = piece_start;
    }
    if (i >= pieces.size()) {
      line(V3(at_.x(), at_.y(), ev.z), Role::Cut);
      continue;
    }
    const Piece& p = pieces[i];
    const double len = p.length();
    const Piece sub = p.part((s - piece_start) / len, std::min(1.0, (ev.s - piece_start) / len));
    if (p.arc && sub.length() >= kTiny) {
      CutMove m;
      m.arc = true;
      m.to = V3(sub.to.x(), sub.to.y(), ev.z);
      m.centre = p.centre;
      m.sweep = sub.sweep;
      path_.moves.push_back(m);
      at_ = m.to;
    } else {
      line(V3(sub.to.x(), sub.to.y(), ev.z), Role::Cut);
    }
    s = ev.s;
    if (ev.s >= ends[i] - kTiny) {
      piece_start = s = ends[i];
      ++i;
    }
  }
}

std::vector<V2> arc_extremes(const V2& from, const V2& centre, double sweep) {
  std::vector<V2> out;
  const double r = (from - centre).norm();
  const double a0 = std::atan2(from.y() - centre.y(), from.x() - centre.x());
  const double q = M_PI / 2;
  // Every multiple of 90 degrees strictly between a0 and a0 + sweep.
  const double lo = std::min(a0, a0 + sweep), hi = std::max(a0, a0 + sweep);
  for (double k = std::floor(lo / q) + 1; k * q < hi; ++k)
    out.push_back(centre + r * V2(std::cos(k * q), std::sin(k * q)));
  return out;
}

}  // namespace gantry::cuts
