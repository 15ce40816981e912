// Tool paths of the cut commands: planar contours (lines and circular arcs), the Z profiles
// laid along them, and the three-dimensional moves that result.
#pragma once

#include <Eigen/Core>  // Vector2d, Vector3d
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gantry/canon/canon_move.hpp"  // SpeedClass

namespace gantry::cuts {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

// A parameter the geometry cannot use: `param` is its 0-based position in the command's
// parameter list, so the command can locate the error.
struct CutError : std::runtime_error {
  CutError(size_t param, const std::string& message) : std::runtime_error(message), param(param) {}
  size_t param;
};

// One planar piece of a contour: a straight line, or a circular arc about `centre` through
// `sweep` radians (positive: counter-clockwise, as CanonMove counts it). A full circle is one
// arc whose `to` equals its `from`.
struct Piece {
  bool arc = false;
  V2 from = V2::Zero(), to = V2::Zero();
  V2 centre = V2::Zero();
  double sweep = 0;

  double radius() const { return (from - centre).norm(); }
  double length() const;
  // The point a fraction `f` (0..1) of the way along.
  V2 at(double f) const;
  // The piece between fractions f0 and f1 of its length.
  Piece part(double f0, double f1) const;
};

// Pieces end to end: each starts where the previous one ends.
using Contour = std::vector<Piece>;
double length(const Contour& c);

// A piecewise-linear function of the distance along a contour, as (distance, value) points
// in increasing distance; constant beyond its ends.
struct Profile {
  std::vector<std::pair<double, double>> points;
  double at(double s) const;
  static Profile constant(double v) { return {{{0.0, v}}}; }
  static Profile ramp(double length, double from, double to) { return {{{0, from}, {length, to}}}; }
};
// The sum of two profiles (breakpoints of both).
Profile operator+(const Profile& a, const Profile& b);

// What a move does, which sets its speed: cutting, plunging and the CP approach at move
// speed; retracts and repositioning above the work at jog speed.
enum class Role { Cut, Plunge, Approach, Retract, Reposition };

struct CutMove {
  bool arc = false;
  V3 to = V3::Zero();
  V2 centre = V2::Zero();  // arc: centre, and sweep in radians (positive counter-clockwise)
  double sweep = 0;
  Role role = Role::Cut;
  SpeedClass speed() const {
    return role == Role::Retract || role == Role::Reposition ? SpeedClass::Jog : SpeedClass::Move;
  }
};

struct CutPath {
  V3 start = V3::Zero();
  std::vector<CutMove> moves;
  int tabs = 0;  // how many tabs the last pass left
  V3 end() const { return moves.empty() ? start : moves.back().to; }
};

// Builds a CutPath from where the tool is: zero-length moves are dropped.
class PathBuilder {
 public:
  explicit PathBuilder(const V3& start) : at_(start) { path_.start = start; }
  const V3& at() const { return at_; }
  void line(const V3& to, Role role);
  void z(double z, Role role) { line(V3(at_.x(), at_.y(), z), role); }
  void xy(const V2& p, Role role) { line(V3(p.x(), p.y(), at_.z()), role); }
  // Follows `c` (which starts at the current XY) with Z given by `z` along its length: each
  // piece is cut at the profile's breakpoints, so Z is linear within every move (a helix on
  // an arc).
  void follow(const Contour& c, const Profile& z);
  CutPath take() { return std::move(path_); }
  CutPath& path() { return path_; }

 private:
  V3 at_;
  CutPath path_;
};

// The points of an arc (start `from`, `sweep` radians about `centre`) where X or Y is
// largest or smallest, besides its ends: where it crosses 0, 90, 180 or 270 degrees.
std::vector<V2> arc_extremes(const V2& from, const V2& centre, double sweep);

}  // namespace gantry::cuts
