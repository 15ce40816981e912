#!/usr/bin/env python3
"""Writes the systematic part of the differential test's corpus (gen_*.ngc): each code of
docs/gcode.md in each plane, unit and distance mode. The CAM outputs, the programs using
features still being built and the refused programs beside them are written by hand.
Run it from anywhere; it rewrites every gen_*.ngc (and removes stale ones)."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
written = {}


def fmt(v):
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def program(name, body, header=None):
    lines = [f"(gen_{name}: written by generate.py)"]
    if header:
        lines.append(header)
    lines += body
    lines.append("M2")
    written[f"gen_{name}.ngc"] = "\n".join(lines) + "\n"


UNITS = {"in": ("G20", 1.0, 20), "mm": ("G21", 25.0, 500)}
# Plane: code, the axes (first, second, third) and each axis's centre word.
PLANES = {
    "xy": ("G17", "XYZ"),
    "zx": ("G18", "ZXY"),
    "yz": ("G19", "YZX"),
}
CENTRE = {"X": "I", "Y": "J", "Z": "K"}


class Writer:
    """Keeps the position so that moves can be written absolute or incremental."""

    def __init__(self, incremental, scale):
        self.inc = incremental
        self.k = scale
        self.pos = {"X": 0.0, "Y": 0.0, "Z": 0.0}

    def axes(self, target):
        words = []
        for a in "XYZ":
            if a in target:
                v = target[a] * self.k
                words.append(a + fmt(v - self.pos[a] if self.inc else v))
        for a in target:
            self.pos[a] = target[a] * self.k
        return " ".join(words)


# ---- lines, each unit and distance mode -----------------------------------------------------
for unit, (ucode, k, feed) in UNITS.items():
    for dist in ("abs", "inc"):
        w = Writer(dist == "inc", k)
        body = [f"{ucode} G17 G{91 if dist == 'inc' else 90} G94 G64"]
        body.append("G0 " + w.axes({"X": 0.5, "Y": 0.25, "Z": 0.5}))
        body.append(f"G1 {w.axes({'Z': -0.125})} F{fmt(feed / 4)}")
        for x, y in ((2, 0.25), (2, 1.5), (0.5, 1.5), (0.5, 0.25), (1.25, 0.875)):
            body.append("G1 " + w.axes({"X": x, "Y": y}) + (f" F{fmt(feed)}" if x == 2 and y == 0.25 else ""))
        body.append(w.axes({"X": 3.1, "Y": -0.7, "Z": -0.2}))  # modal G1, three axes
        body.append("G0 " + w.axes({"Z": 0.75}))
        body.append(w.axes({"X": -1.3}))  # modal G0
        body.append(f"G1 {w.axes({'X': 0.3, 'Y': 0.4, 'Z': 0.1})} F{fmt(feed * 1.7)}")
        body.append("G0 " + w.axes({"X": 0, "Y": 0, "Z": 1}))
        program(f"lines_{unit}_{dist}", body)

# ---- arcs: each plane, unit, distance mode and centre form ----------------------------------
def arc_program(plane, unit, dist, form):
    pcode, axes = PLANES[plane]
    u, v, wax = axes
    ucode, k, feed = UNITS[unit]
    w = Writer(dist == "inc", k)
    body = [f"{ucode} {pcode} G{91 if dist == 'inc' else 90} G91.1 G94 F{fmt(feed)}"]
    body.append("G0 " + w.axes({u: 1.0, v: 0.0, wax: 0.5}))
    cur = {u: 1.0, v: 0.0, wax: 0.5}

    def arc(code, end, centre, extra=""):
        # centre: absolute (first, second) in program units before scaling
        nonlocal cur
        words = [code, w.axes(end)]
        if form == "ijk":
            words.append(CENTRE[u] + fmt((centre[0] - cur[u]) * k))
            words.append(CENTRE[v] + fmt((centre[1] - cur[v]) * k))
        else:
            r = math.hypot(cur[u] - centre[0], cur[v] - centre[1]) * k
            # the long way round: R negative (more than 180 degrees)
            a0 = math.atan2(cur[v] - centre[1], cur[u] - centre[0])
            a1 = math.atan2(end.get(v, cur[v]) - centre[1], end.get(u, cur[u]) - centre[0])
            sweep = a1 - a0
            if code == "G2":
                sweep = sweep if sweep < 0 else sweep - 2 * math.pi
            else:
                sweep = sweep if sweep > 0 else sweep + 2 * math.pi
            words.append("R" + fmt(-r if abs(sweep) > math.pi else r))
        if extra:
            words.append(extra)
        body.append(" ".join(x for x in words if x))
        cur = {**cur, **end}

    arc("G3", {u: 0.0, v: 1.0}, (0, 0))                      # a quarter, counter-clockwise
    arc("G2", {u: 1.0, v: 0.0}, (0, 0))                      # back, clockwise
    arc("G2", {u: 0.0, v: -1.0}, (0, 0))                     # a quarter clockwise
    arc("G3", {u: -1.0, v: 0.0}, (0, 0))                     # three quarters counter-clockwise
    arc("G2", {u: 0.0, v: 1.0, wax: 0.25}, (0, 0))           # a helix, a quarter turn down
    arc("G3", {u: 0.5, v: 1.5}, (0.5, 1.0))                  # three quarters about another centre
    arc("G2", {u: 1.0, v: 1.0}, (0.5, 1.0))                  # a quarter clockwise
    arc("G3", {u: 1.4, v: 1.0}, (1.2, 1.0))                  # half a circle, small radius
    arc("G2", {u: 1.2, v: 1.2}, (1.2, 1.0))                  # three quarters clockwise
    if form == "ijk":
        arc("G2", {u: 1.2, v: 1.2}, (1.2, 0.7))              # a full circle, end = start
        arc("G3", {u: 1.2, v: 1.2, wax: 0.0}, (1.2, 0.7), "P2")  # two turns, a helix
        arc("G2", {u: 0.7, v: 0.7, wax: 0.3}, (1.2, 0.7), "P3")  # two turns and 3/4
    body.append("G0 " + w.axes({u: 0.0, v: 0.0, wax: 1.0}))
    program(f"arcs_{plane}_{unit}_{dist}_{form}", body)


for plane in PLANES:
    for unit in UNITS:
        for dist in ("abs", "inc"):
            for form in ("ijk", "r"):
                arc_program(plane, unit, dist, form)

# ---- absolute arc centres (G90.1), full circles without an end point ------------------------
for plane, (pcode, axes) in PLANES.items():
    u, v, wax = axes
    for unit, (ucode, k, feed) in UNITS.items():
        body = [f"{ucode} {pcode} G90 G90.1 F{fmt(feed)}",
                f"G0 {u}{fmt(2 * k)} {v}{fmt(1 * k)} {wax}{fmt(0.2 * k)}",
                f"G2 {u}{fmt(1 * k)} {v}{fmt(2 * k)} {CENTRE[u]}{fmt(1 * k)} {CENTRE[v]}{fmt(1 * k)}",
                f"G3 {u}{fmt(0 * k)} {v}{fmt(1 * k)} {CENTRE[u]}{fmt(1 * k)} {CENTRE[v]}{fmt(1 * k)} {wax}{fmt(-0.1 * k)}",
                f"G91.1 G2 {u}{fmt(1 * k)} {v}{fmt(0)} {CENTRE[u]}{fmt(1 * k)} {CENTRE[v]}{fmt(0)}"]
        program(f"arcs_abs_centre_{plane}_{unit}", body)
    body = [f"G20 {pcode} G90 F30", f"G0 {u}1 {v}0 {wax}0",
            f"G2 {CENTRE[u]}0.5 {CENTRE[v]}0",          # no end point: a full circle
            f"G3 {CENTRE[u]}-0.25 {CENTRE[v]}0.25 P2",  # two turns
            f"G2 {wax}-0.5 {CENTRE[u]}0.5",             # a full helical turn
            f"G91 G3 {CENTRE[v]}0.3 {wax}-0.1 P3",      # incremental, three turns down
            f"G90 G0 {wax}1"]
    program(f"full_circles_{plane}", body)

# ---- work offsets ---------------------------------------------------------------------------
SYSTEMS = ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"]
for unit, (ucode, k, feed) in UNITS.items():
    body = [f"{ucode} G17 G90 F{feed}"]
    for p, code in enumerate(SYSTEMS, start=1):
        body.append(f"G10 L2 P{p} X{fmt(p * 0.5 * k)} Y{fmt(-p * 0.25 * k)} Z{fmt(p * 0.1 * k)}")
    for code in SYSTEMS:
        body += [f"{code}", "G0 X0 Y0 Z0", "G1 X1 Y0.5", "G0 Z0.5"]
    body += ["G10 L2 P0 X3 Y3", "G0 X0 Y0", "G54 G0 X0 Y0"]
    program(f"work_systems_{unit}", body)
    body = [f"{ucode} G90 F{feed}", "G0 X1 Y1 Z1",
            "G10 L20 P1 X0 Y0", "G0 X0.5 Y0.5",                  # the current point reads 0,0
            "G55 G10 L20 P0 Z0.25", "G0 Z0", "G1 X0.1 F10",
            "G10 L20 P3 X2", "G56 G0 X2 Y0", "G54 G0 X0 Y0", "G91 G10 L20 P2 X0", "G90 G55 G0 X0"]
    program(f"g10_l20_{unit}", body)
    body = [f"{ucode} G90 F{feed}", "G0 X2 Y1 Z0.5", "G92 X0 Y0", "G0 X1 Y1",
            "G92.2", "G0 X1 Y1", "G92.3", "G0 X1 Y1", "G92 Z0", "G1 Z-0.1", "G92.1",
            "G0 X0 Y0 Z0", "G10 L2 P1 X1", "G0 X1", "G92 X0", "G55 G0 X0 Y0", "G54 G0 X0", "G92.1", "G0 X0"]
    program(f"g92_{unit}", body)
    for dist in ("abs", "inc"):
        d = "G91" if dist == "inc" else "G90"
        body = [f"{ucode} G90 F{feed}", "G0 X1 Y2 Z0.5", "G28.1", "G0 X3 Y1 Z0.2", "G30.1",
                "G0 X0 Y0 Z0", f"{d} G28", f"{d} G30", "G90 G0 X0 Y0 Z0",
                f"{d} G28 Z0.5", f"{d} G30 X0.5 Y0.5", "G90 G0 X0.25 Y0.25",
                "G10 L2 P1 X1 Y1", "G28", "G0 X0 Y0", "G30 Z1", "G10 L2 P1 X0 Y0", "G0 X0 Y0"]
        program(f"g28_g30_{unit}_{dist}", body)
    body = [f"{ucode} G90 F{feed}", "G10 L2 P1 X1 Y1 Z-0.5", "G0 X0 Y0 Z0", "G53 G0 X0 Y0",
            "G53 G1 Z0.25", "G0 X1", "G92 X0", "G53 G0 X2 Z0", "G0 X0",
            "G0 Y0", "G43.1 Z0.3", "G53 G0 Z0", "G0 Z0", "G49 G92.1 G53 G0 X0 Y0 Z0"]
    program(f"g53_{unit}", body)
    body = [f"{ucode} G90 F{feed}", "G0 X1 Y1 Z1", "G1 Z0.2", "G43.1 Z0.2", "G0 Z0",
            "G1 X2", "G43.1 Z-0.1", "G1 Z0", "G91 G43.1 Z0.3", "G0 Z0.1", "G90 G49", "G0 Z0",
            "G43.1 Z0.5", f"G21 G0 Z0", "G20 G0 Z0", f"{ucode} G49 G0 Z1"]
    program(f"g43_1_{unit}", body)

# ---- feed modes, path modes, dwell ----------------------------------------------------------
for unit, (ucode, k, feed) in UNITS.items():
    body = [f"{ucode} G90 G17", "G0 X0 Y0 Z0", "G93 G1 X1 F10", "G1 Y1 Z-0.1 F30",
            "G2 X0 Y0 I-0.5 J-0.5 F4", "G3 X1 Y1 R1 F6", "G1 X1.5 F120",
            f"G94 G1 X0 F{feed}", "G1 Y0"]
    program(f"g93_{unit}", body)
body = ["G20 G90 F30", "G0 X0 Y0 Z0.1", "G61", "G1 X1", "G1 Y1", "G2 X0 Y1 I-0.5", "G0 Z0.5",
        "G64", "G1 X1", "G1 Y0", "G61.1", "G1 X0.5", "G1 Y0.5", "G64 P0.01", "G1 X0", "G1 Y0",
        "G61 G1 Y1", "G64 G1 X0"]
program("path_modes", body)
# G64's Q: the naive CAM tolerance.
program("path_blend_q", ["G21 G90 F300", "G64 P0.1 Q0.05", "G1 X10", "G1 Y10", "G1 X0", "G1 Y0"])
body = ["G20 G90 F30", "G0 X0 Y0", "G4 P1.5", "G1 X1", "G4 P0.25", "G4 P0", "G1 Y1",
        "G4 P2 G0 Z1", "G21 G4 P0.75", "G1 X0 F300"]
program("dwell", body)

# ---- canned cycles: each cycle, retract mode, distance mode, unit, repeats -------------------
CYCLES = {"g81": "", "g82": "P0.5", "g83": "Q0.33", "g73": "Q0.27"}
for cyc, extra in CYCLES.items():
    for unit, (ucode, k, feed) in UNITS.items():
        for ret in ("G98", "G99"):
            for dist in ("abs", "inc"):
                q = extra
                if extra.startswith("Q"):
                    q = "Q" + fmt(float(extra[1:]) * k)
                c = cyc.upper()
                if dist == "abs":
                    body = [f"{ucode} G17 G90 F{feed}", f"G0 X0 Y0 Z{fmt(0.6 * k)}",
                            f"{ret} {c} X{fmt(1 * k)} Y{fmt(1 * k)} Z{fmt(-0.75 * k)} R{fmt(0.1 * k)} {q}",
                            f"X{fmt(2 * k)}", f"Y{fmt(2 * k)} Z{fmt(-0.5 * k)}",
                            f"X{fmt(4 * k)} Y{fmt(1.5 * k)}",
                            "G80", f"G0 Z{fmt(0.3 * k)}",
                            f"{ret} {c} X{fmt(0.5 * k)} Y{fmt(0.5 * k)} Z{fmt(-0.2 * k)} R{fmt(0.5 * k)} {q}",
                            "G80", f"G0 X0 Y0 Z{fmt(1 * k)}"]
                else:
                    body = [f"{ucode} G17 G90 F{feed}", f"G0 X0 Y0 Z{fmt(0.6 * k)}",
                            f"G91 {ret} {c} X{fmt(1 * k)} Y{fmt(0.5 * k)} Z{fmt(-0.8 * k)} R{fmt(-0.5 * k)} {q} L3",
                            "G90 G80", f"G0 X0 Y0 Z{fmt(1 * k)}"]
                program(f"cycle_{cyc}_{unit}_{ret.lower()}_{dist}", body)
# A cycle that starts below R rises to R first; the cycle's modal axes; G80 in the motion group.
program("cycle_below_r", ["G20 G90 F20", "G0 X0 Y0 Z0", "G98 G81 X1 Y1 Z-0.5 R0.2",
                          "G99 G81 X2 Y1 Z-0.5 R0.2", "G0 Z-0.1", "G98 G83 X3 Y1 Z-0.6 R0.1 Q0.3",
                          "G80", "G0 Z1"])
# The retract mode changed within a series: G98 goes back to where the series began.
program("cycle_mode_switch", ["G20 G17 G90 F20", "G0 X0 Y0 Z0.6", "G98 G81 X1 Y1 Z-0.75 R0.1",
                              "G99 X2", "X3", "G98 X4", "G80", "G0 Z1"])
# R raised within a series of G99 cycles.
program("cycle_r_raised", ["G20 G17 G90 F20", "G0 X0 Y0 Z0.6", "G99 G81 X1 Y1 Z-0.75 R0.1",
                           "X2 R0.2", "X3", "G80", "G0 Z1"])
# Incremental cycles continued by later blocks without R and Z.
program("cycle_inc_continued", ["G21 G17 G90 F300", "G0 X0 Y0 Z15",
                                "G91 G99 G81 X25 Y12.5 Z-20 R-12.5 L2", "X-12.5 Y0",
                                "X0 Y20 L2", "G90 G80", "G0 X0 Y0 Z25"])
# A depth that is a whole number of pecks, in millimetres.
program("cycle_peck_multiple", ["G21 G90 F200", "G0 X0 Y0 Z15", "G98 G83 X25 Y25 Z-12.5 R2.5 Q7.5",
                                "G73 X50 Z-12.5 R2.5 Q5", "G80", "G0 Z15"])
program("cycle_modal", ["G21 G90 F200", "G0 X0 Y0 Z10", "G81 X10 Y10 Z-3 R2", "Y20", "X20",
                        "Z-5", "R5 X30", "G82 P0.2 R5 Z-5 X40", "G80", "G0 Z10"])

# ---- expressions and parameters ---------------------------------------------------------------
program("expressions", [
    "G20 G90 F[10*3]", "#1 = 0.5", "#2 = [#1 * 4]", "#3 = [#2 / 8 + 1]",
    "G0 X#1 Y#2 Z#3", "G1 X[#1 + #2] Y[#2 - #1 * 2] F[#2 * 15]",
    "G1 X[SIN[30] * 2] Y[COS[60] * 2]", "G1 X[SQRT[2] ** 2] Y[ABS[-1.25]]",
    "G1 X[ATAN[1]/[1] / 45] Y[2 MOD 0.75]", "G1 X[FIX[1.7]] Y[FUP[1.2]]",
    "G1 X[ROUND[1.49]] Y[EXP[0] + LN[1]]", "G1 X[TAN[45]] Y[ASIN[1] / 90 + ACOS[1]]",
    "G1 X[1 + 2 * 3 - 4 / 2] Y[[1 + 2] * [3 - 4] / 2 + 3]",
    "G1 X[1 GT 0] Y[[2 LE 1] + [3 EQ 3] * 2]", "G1 X[1 AND 0] Y[1 OR 0 + 1 XOR 1]",
    "G1 X[-[-1]] Y[- 2 + 3]", "#4 = 2 #5 = #4", "G1 X#5 Y#4",
    "#10 = 1.5", "#11 = #10", "#10 = 2.5 G1 X#10 Y#11",
])
# Indirect parameters: #[expression].
program("param_indirect", ["G20 G90 F30", "#1 = 2", "#[#1 + 1] = 0.25", "G1 X#3 Y#[1+1]",
                           "#[#1 * 5] = 1.5", "G1 X#10"])
program("parameters_offsets", [
    "G20 G90 F30", "G10 L2 P2 X1 Y2 Z0.5", "G0 X[#5241] Y[#5242]",
    "G55 G0 X0 Y0", "G0 X[#5220] Y0", "G92 X1", "G0 X[#5211] Y0", "G92.1",
    "G0 X1 Y1 Z0.25", "G28.1", "G0 X[#5161 + 1] Y[#5162] Z[#5163]", "G54 G0 X0 Y0 Z0",
])

# ---- M codes ----------------------------------------------------------------------------------
program("m_codes", [
    "G20 G90 F30", "G0 X0 Y0 Z1", "M3 S12000", "G1 Z0", "M8", "G1 X1", "M7", "G1 Y1", "M9",
    "G1 X0", "M5", "G0 Z1", "M3 S9000 M8", "G1 X0.5", "M5 M9", "G0 X0 Y0", "M1", "G0 X0.1",
])
program("m_codes_outputs", [
    "G21 G90 F600", "G0 X0 Y0 Z5", "M64 P5", "G1 X10", "M65 P5", "M62 P6 G1 X20", "M63 P6",
    "G1 X30", "M3 S18000", "G0 Z1", "M0", "G1 X0", "M5",
])
program("m30_end", ["G20 G90 F30", "G0 X1 Y1", "M3 S10000", "G1 X2", "M30 (end, the spindle stops)"])

# ---- G38 probes -------------------------------------------------------------------------------
program("probe", ["G20 G90 F10", "G0 X1 Y1 Z1", "G38.2 Z-1", "G0 Z1", "G38.3 Z-0.5 F5",
                  "G0 Z1", "G0 X0"])

# ---- codes Gantry refuses by name (docs/gcode.md): LinuxCNC runs them --------------------------
REFUSED = {
    "g52": ["G0 X1 Y1", "G52 X2 Y2", "G0 X0 Y0", "G52 X0 Y0"],
    "g43_2": ["T1 M6", "G43 H1", "G43.2 H2", "G0 Z0"],
    "g95": ["S1000 M3", "G95 F0.01", "G1 X1", "G94 M5"],
    "g96": ["G96 D2000 S300 M3", "G0 X1", "G97 S1000", "M5"],
    "g5_2": ["F30", "G5.2 X0 Y0 P1 L3", "X1 Y0 P1", "X1 Y1 P1", "G5.3"],
    "g7_lathe": ["G18 G7", "G0 X1", "G8 G17"],
    "g17_1": ["G17.1", "G0 X1", "G17"],
    "g33_sync": ["S500 M3", "G33 Z-0.5 K0.05", "M5"],
    "m19_orient": ["S500 M3", "M19 R90", "M5"],
    "m48_overrides": ["M49", "G0 X1", "M48"],
    "m52_adaptive": ["M52 P1", "G0 X1", "M52 P0"],
    "m60_pallet": ["G0 X1", "M60", "G0 X2"],
    "m61_set_tool": ["M61 Q1", "G43", "G0 Z0"],
    "m66_wait": ["M66 P0 L0", "G0 X1"],
    "m67_analog": ["M68 E0 Q2.5", "G0 X1"],
    "m70_modal_state": ["M70", "G91", "M72", "G0 X1"],
}
for name, lines in REFUSED.items():
    program(f"refused_{name}", ["G20 G90 G17"] + lines)

for old in os.listdir(HERE):
    if old.startswith("gen_") and old.endswith(".ngc") and old not in written:
        os.remove(os.path.join(HERE, old))
for name, text in written.items():
    with open(os.path.join(HERE, name), "w") as f:
        f.write(text)
print(f"{len(written)} programs written")
