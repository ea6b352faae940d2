"""The room with a box (examples/meshes/room_with_box.obj), its floor heated to 35 C, its ceiling
at 18 C, the walls and the box adiabatic: the temperature each adiabatic surface settles at, the
heat that flows, and the energy balance. Run from the repository's root:
    PYTHONPATH=build/python python3 examples/python/thermal_room.py [--level L]"""
import argparse
import json

import panelrad

parser = argparse.ArgumentParser()
parser.add_argument("--level", type=int, default=3)
args = parser.parse_args()
scene = panelrad.load_scene("examples/meshes/room_with_box.obj", geometry_only=True)
with open("examples/thermal/room_with_box.json") as f:
    conditions = json.load(f)["groups"]  # the same conditions as `panelrad thermal --bc`
s = panelrad.thermal_solve(scene, conditions, "object", level=args.level)
for name, area, T, Q in zip(s.names, s.group_area, s.group_T, s.group_Q):
    print(f"{name:10s} {area:6.3f} m^2 {T:9.3f} K {Q:10.4f} W")
print(f"energy balance: sum of the rates {s.group_Q.sum():.3e} W, defect {s.balance_defect:.2e}")
