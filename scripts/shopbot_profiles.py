#!/usr/bin/env python3
"""Writes settings/profiles/*.toml, the shipped ShopBot profiles, from settings/default.toml.

One table below holds every number that differs between the tables, each with where it comes
from; everything else (pins, inputs, values, planner) is the default profile's. The millimetre
twin of each profile is the inch one converted as `VD` converts a profile (src/settings/units.cpp;
settings_test.cpp checks that the two agree). Run it after changing default.toml or a number
here:  python3 scripts/shopbot_profiles.py
"""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent

# name: (title, numbers in inches). Sources (docs/settings.md lists them):
#  [F] FabMo-Engine's profiles (profiles/*/config/machine.json "envelope"): the XY area of the
#      Desktop (24 x 18), Desktop MAX (36 x 24) and Handibot (6 x 8).
#  [D] drshopbot.com, "My ShopBot is not moving the correct distance": speeds for a PRSstandard
#      (XY move 2-4 in/s, jog 4-6; Z move 1.5, jog 3) and a PRSalpha (XY move 4, jog 12).
#  [H] handibot.support, "Cut Area": a Handibot cuts 6 x 8 in.
#  [G] Gantry's default profile (settings/default.toml): a Desktop's unit values and speeds.
#  [N] the model's name: PRS 48x96 and 60x120 are the nominal cutting areas, Y x X.
#  chosen: not published in the sources found; a sane value, said so in the profile.
TABLES = {
    "shopbot-desktop": ("ShopBot Desktop 24x18", dict(
        x=(24, "F"), y=(18, "F"), z=(5.5, "G"), xy_spu=(916.7324, "G"), z_spu=(1018.5916, "G"),
        xy_max=(8.0, "G"), z_max=(4.0, "G"), xy_acc=(20.0, "G"), z_acc=(16.0, "G"),
        move_xy=(2.0, "G"), move_z=(0.5, "G"), jog_xy=(6.0, "G"), jog_z=(3.0, "G"),
        home_fast=(1.0, "G"))),
    "shopbot-desktop-max": ("ShopBot Desktop MAX 36x24", dict(
        x=(36, "F"), y=(24, "F"), z=(5.5, "chosen"), xy_spu=(916.7324, "chosen"),
        z_spu=(1018.5916, "chosen"), xy_max=(8.0, "chosen"), z_max=(4.0, "chosen"),
        xy_acc=(20.0, "chosen"), z_acc=(16.0, "chosen"), move_xy=(2.0, "chosen"),
        move_z=(0.5, "chosen"), jog_xy=(6.0, "chosen"), jog_z=(3.0, "chosen"),
        home_fast=(1.5, "chosen"))),
    "prsalpha-48x96": ("ShopBot PRSalpha 48x96", dict(
        x=(96, "N"), y=(48, "N"), z=(8.0, "chosen"), xy_spu=(1273.2395, "chosen"),
        z_spu=(1273.2395, "chosen"), xy_max=(15.0, "chosen"), z_max=(6.0, "chosen"),
        xy_acc=(30.0, "chosen"), z_acc=(20.0, "chosen"), move_xy=(4.0, "D"),
        move_z=(1.5, "chosen"), jog_xy=(12.0, "D"), jog_z=(4.0, "chosen"),
        home_fast=(3.0, "chosen"))),
    "prsalpha-60x120": ("ShopBot PRSalpha 60x120", dict(
        x=(120, "N"), y=(60, "N"), z=(8.0, "chosen"), xy_spu=(1273.2395, "chosen"),
        z_spu=(1273.2395, "chosen"), xy_max=(15.0, "chosen"), z_max=(6.0, "chosen"),
        xy_acc=(30.0, "chosen"), z_acc=(20.0, "chosen"), move_xy=(4.0, "D"),
        move_z=(1.5, "chosen"), jog_xy=(12.0, "D"), jog_z=(4.0, "chosen"),
        home_fast=(3.0, "chosen"))),
    "prsstandard-48x96": ("ShopBot PRSstandard 48x96", dict(
        x=(96, "N"), y=(48, "N"), z=(6.0, "chosen"), xy_spu=(1018.5916, "chosen"),
        z_spu=(1018.5916, "chosen"), xy_max=(8.0, "chosen"), z_max=(4.0, "chosen"),
        xy_acc=(20.0, "chosen"), z_acc=(16.0, "chosen"), move_xy=(3.0, "D"),
        move_z=(1.5, "D"), jog_xy=(6.0, "D"), jog_z=(3.0, "D"), home_fast=(2.0, "chosen"))),
    "prsstandard-60x120": ("ShopBot PRSstandard 60x120", dict(
        x=(120, "N"), y=(60, "N"), z=(6.0, "chosen"), xy_spu=(1018.5916, "chosen"),
        z_spu=(1018.5916, "chosen"), xy_max=(8.0, "chosen"), z_max=(4.0, "chosen"),
        xy_acc=(20.0, "chosen"), z_acc=(16.0, "chosen"), move_xy=(3.0, "D"),
        move_z=(1.5, "D"), jog_xy=(6.0, "D"), jog_z=(3.0, "D"), home_fast=(2.0, "chosen"))),
    "handibot": ("Handibot 6x8", dict(
        x=(6, "H"), y=(8, "H"), z=(4.0, "chosen"), xy_spu=(916.7324, "chosen"),
        z_spu=(1018.5916, "chosen"), xy_max=(6.0, "F"), z_max=(6.0, "chosen"),
        xy_acc=(15.0, "chosen"), z_acc=(16.0, "chosen"), move_xy=(2.0, "F"),
        move_z=(0.5, "chosen"), jog_xy=(6.0, "F"), jog_z=(3.0, "chosen"),
        home_fast=(1.0, "chosen"))),
}

SOURCE = {"F": "FabMo-Engine's profile", "D": "drshopbot.com", "H": "handibot.support",
          "G": "Gantry's Desktop default", "N": "the model's name", "chosen": "chosen, not published"}


def inch_values(t):
    v = {k: n for k, (n, _) in t.items()}
    src = {k: s for k, (_, s) in t.items()}
    out = {
        ("axes.x", "steps_per_unit"): (v["xy_spu"], src["xy_spu"]),
        ("axes.y", "steps_per_unit"): (v["xy_spu"], src["xy_spu"]),
        ("axes.z", "steps_per_unit"): (v["z_spu"], src["z_spu"]),
        ("axes.x", "max_speed"): (v["xy_max"], src["xy_max"]),
        ("axes.y", "max_speed"): (v["xy_max"], src["xy_max"]),
        ("axes.z", "max_speed"): (v["z_max"], src["z_max"]),
        ("axes.x", "max_accel"): (v["xy_acc"], src["xy_acc"]),
        ("axes.y", "max_accel"): (v["xy_acc"], src["xy_acc"]),
        ("axes.z", "max_accel"): (v["z_acc"], src["z_acc"]),
        ("axes.x", "max"): (v["x"], src["x"]),
        ("axes.y", "max"): (v["y"], src["y"]),
        # Z 0 is wherever it is zeroed (C2 on the material, C3 at the top): the envelope lets
        # Z travel its whole length either way from it.
        ("axes.z", "min"): (-v["z"], src["z"]),
        ("axes.z", "max"): (v["z"], src["z"]),
        ("speeds.move", "xy"): (v["move_xy"], src["move_xy"]),
        ("speeds.move", "z"): (v["move_z"], src["move_z"]),
        ("speeds.jog", "xy"): (v["jog_xy"], src["jog_xy"]),
        ("speeds.jog", "z"): (v["jog_z"], src["jog_z"]),
        ("preview", "table_x"): (v["x"], src["x"]),
        ("preview", "table_y"): (v["y"], src["y"]),
        ("preview", "table_z"): (v["z"], src["z"]),
        ("homing", "fast_speed"): (v["home_fast"], src["home_fast"]),
    }
    return out


# Keys whose value is a length (or a speed or an acceleration): x 25.4 in millimetres, as
# convert_units does; steps per unit / 25.4. A, B and C stay in degrees.
LENGTH_KEYS = {
    "axes.x": {"max_speed", "max_accel", "min", "max"}, "axes.y": {"max_speed", "max_accel", "min", "max"},
    "axes.z": {"max_speed", "max_accel", "min", "max"},
    "speeds.move": {"xy", "z"}, "speeds.jog": {"xy", "z"},
    "ramps": {"move_ramp_rate", "jog_ramp_rate", "min_distance", "keypad_ramp_rate", "small_circle"},
    "ramps.move_speed": {"xy", "z"}, "ramps.jog_speed": {"xy", "z"},
    "planner": {"junction_deviation", "chord_tolerance", "jerk"},
    "cutter": {"diameter", "safe_z", "trigger_on", "trigger_off"},
    "tabs": {"pull_up", "spacing", "size", "leads"},
    "display": {"keypad_step"},
    "preview": {"grid", "table_x", "table_y", "table_z"},
    "calibration": {"circle_resolution"},
    "homing": {"fast_speed", "slow_speed", "back_off"},
    "homing.x": {"at"}, "homing.y": {"at"}, "homing.z": {"at"},
    "simulator": {"home_x", "home_y", "home_z", "plate_z"},
}
PER_LENGTH_KEYS = {"axes.x": {"steps_per_unit"}, "axes.y": {"steps_per_unit"}, "axes.z": {"steps_per_unit"}}


def round12(x):
    return float(f"{x:.12g}")


def number(x):
    return repr(round12(x)) if x != int(x) or abs(x) >= 1e15 else f"{x:.1f}"


LINE = re.compile(r"^(\s*)([a-z_0-9]+)(\s*=\s*)([^#\n]*?)(\s*)(#.*)?$")


def render(text, title, values, mm):
    out, table = [], ""
    for line in text.splitlines():
        header = re.match(r"^\[([a-z_.]+)\]", line)
        if header:
            table = header.group(1)
            out.append(line)
            continue
        m = LINE.match(line)
        if not m or line.lstrip().startswith("#"):
            out.append(line)
            continue
        indent, key, eq, value, space, comment = m.groups()
        comment = comment or ""
        if table == "" and key == "name":
            value = f'"{title} ({"mm" if mm else "inches"})"'
        elif table == "" and key == "units":
            value = '"mm"' if mm else '"in"'
        elif (table, key) in values:
            n, src = values[(table, key)]
            if mm:
                n = n / 25.4 if key in PER_LENGTH_KEYS.get(table, ()) else n * 25.4
            value = number(n)
            comment = f"# {SOURCE[src]}" if src in SOURCE else comment
        elif mm and key in LENGTH_KEYS.get(table, ()):
            value = number(float(value) * 25.4)
        elif mm and key in PER_LENGTH_KEYS.get(table, ()):
            value = number(float(value) / 25.4)
        pad = "  " if comment and not space else space
        out.append(f"{indent}{key}{eq}{value}{pad if comment else ''}{comment}".rstrip())
    return "\n".join(out) + "\n"


def main():
    text = (ROOT / "settings/default.toml").read_text()
    body = text.split("\n", 3)[3]  # the default's own title lines go
    for name, (title, table) in TABLES.items():
        values = inch_values(table)
        for mm in (False, True):
            head = (f"# Gantry machine profile: {title}, {'millimetres' if mm else 'inches'}.\n"
                    "# Written by scripts/shopbot_profiles.py from settings/default.toml; each number\n"
                    "# that differs from it says where it comes from (docs/settings.md, \"Shipped profiles\").\n")
            path = ROOT / "settings/profiles" / f"{name}{'-mm' if mm else ''}.toml"
            path.write_text(head + render(body, title, values, mm))


if __name__ == "__main__":
    main()
