// Cutter radius compensation's state between blocks (gcode_cutter_comp.cpp). Private to
// src/interp.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "gantry/interp/gcode_executor.hpp"

namespace gantry {

// What compensation knows between blocks. Coordinates are program coordinates in machine
// units (as program_position()).
struct GcodeExecutor::Comp {
  int side = 0;  // +1 G41 (left), -1 G42 (right), 0 off
  double radius = 0;
  bool first = true;              // the next move is the entry move
  bool arc_not_allowed = false;   // just after G40: the next move must be straight
  std::optional<Vec6> exit_base;  // after G40: where the next move starts, as programmed
  Vec6 prog = Vec6::Zero();       // the last programmed end point
  Vec6 cur = Vec6::Zero();        // where the tool is once the held-back moves are made
  struct Pending {
    enum class Kind { Line, Arc, Action } kind = Kind::Line;
    Vec6 end = Vec6::Zero();
    double du = 0, dv = 0;        // a line: its programmed direction
    double cu = 0, cv = 0;        // an arc: its centre
    int turn = 0;                 // an arc: turns, + counter-clockwise
    double programmed_sweep = 0;  // an arc: its sweep before its end was moved
    SpeedClass cls = SpeedClass::Move;
    double speed = 0;
    SourceLoc loc;
    std::function<void()> action;
  };
  std::vector<Pending> queue;
  // Where the first held-back move starts (valid: it starts at a known corner).
  double start_u = 0, start_v = 0;
  bool start_valid = false;

  void set_start(double u, double v) {
    start_u = u;
    start_v = v;
    start_valid = true;
  }
  const Pending* front_move() const {
    return queue.empty() || queue.front().kind == Pending::Kind::Action ? nullptr : &queue.front();
  }
  bool front_is_arc() const { return !queue.empty() && queue.front().kind == Pending::Kind::Arc; }
  void push_line(const Vec6& end, double du, double dv, SpeedClass cls, double speed,
                 const SourceLoc& loc) {
    Pending p;
    p.kind = Pending::Kind::Line;
    p.end = end;
    p.du = du;
    p.dv = dv;
    p.cls = cls;
    p.speed = speed;
    p.loc = loc;
    queue.push_back(std::move(p));
  }
  void push_arc(const Vec6& end, double cu, double cv, int turn, double programmed_sweep,
                double speed, const SourceLoc& loc) {
    Pending p;
    p.kind = Pending::Kind::Arc;
    p.end = end;
    p.cu = cu;
    p.cv = cv;
    p.turn = turn;
    p.programmed_sweep = programmed_sweep;
    p.speed = speed;
    p.loc = loc;
    queue.push_back(std::move(p));
  }
  // Sends the held-back moves and actions as they are.
  void send_all(GcodeExecutor& ex);
  // Moves every held-back move's end to (u, v) in the plane, refusing a move that would
  // then run backwards (the tool cannot reach the corner without gouging), and sends them.
  void flush_to(GcodeExecutor& ex, double u, double v, const SourceLoc& loc);
};

}  // namespace gantry
