#!/usr/bin/env python3
"""Writes scenes/robocup2006.json, scenes/incidence-rings.json and scenes/tiled-room.json.

The JSON files are the source of truth (and committed); this script documents how their numbers
were chosen and regenerates them: python3 scenes/tools/make_scenes.py
"""
import json
import math
import pathlib

SCENES = pathlib.Path(__file__).resolve().parent.parent


def dump(name, scene):
    text = json.dumps(scene, indent=1)
    (SCENES / name).write_text(text + "\n")


# ---------------------------------------------------------------- RoboCup 2006 Four-Legged field
FIELD_X, FIELD_Y = 5.4, 3.6          # field of play (m), +X along the long axis to the yellow goal
MARGIN = 0.3                         # green carpet beyond the field lines on every side
LINE = 0.025                         # white line width
LINE_Z = 0.001                       # lines are painted 1 mm above the carpet (no coplanar faces)
CENTRE_CIRCLE_D = 0.36               # centre circle diameter (to the line's centre)
PENALTY_W, PENALTY_D = 1.3, 0.65     # penalty area: width along Y, depth along X
GOAL_W, GOAL_H, GOAL_D = 0.8, 0.3, 0.25  # goal mouth width, height, depth behind the goal line
# (0.25 m leaves a gap before the border wall: coplanar faces would make engines disagree)
GOAL_WALL = 0.02                     # thickness of goal walls and crossbar
BORDER_H, BORDER_T = 0.10, 0.05      # low white border wall around the carpet
BEACON_D, BEACON_H = 0.10, 0.40      # beacon cylinder: white lower 0.20 m, two 0.10 m bands
BEACON_X, BEACON_OUT = 1.35, 0.15    # |x| from halfway line; centre 0.15 m outside the long edge


def quad(name, material, x0, y0, x1, y1, z):
    return {"name": name, "type": "quad", "material": material,
            "origin": [x0, y0, z], "edge_u": [x1 - x0, 0, 0], "edge_v": [0, y1 - y0, 0]}


def box(name, material, cx, cy, cz, sx, sy, sz):
    return {"name": name, "type": "box", "material": material,
            "center": [cx, cy, cz], "size": [sx, sy, sz]}


def robocup2006():
    hx, hy = FIELD_X / 2, FIELD_Y / 2
    cx, cy = hx + MARGIN, hy + MARGIN
    objects = [quad("carpet", "carpet", -cx, -cy, cx, cy, 0.0)]
    # Boundary lines, their outer edge on the field boundary.
    objects += [
        quad("line_bottom", "line", -hx, -hy, hx, -hy + LINE, LINE_Z),
        quad("line_top", "line", -hx, hy - LINE, hx, hy, LINE_Z),
        quad("line_left", "line", -hx, -hy + LINE, -hx + LINE, hy - LINE, LINE_Z),
        quad("line_right", "line", hx - LINE, -hy + LINE, hx, hy - LINE, LINE_Z),
        quad("line_halfway", "line", -LINE / 2, -hy + LINE, LINE / 2, hy - LINE, LINE_Z),
    ]
    objects.append({"name": "centre_circle", "type": "disc", "material": "line",
                    "center": [0, 0, 2 * LINE_Z], "normal": [0, 0, 1],
                    "radius": CENTRE_CIRCLE_D / 2 + LINE / 2, "inner_radius": CENTRE_CIRCLE_D / 2 - LINE / 2,
                    "comment": "annulus on top of the halfway line (2 mm) so the two never share a plane"})
    for side, sign in (("yellow", 1), ("blue", -1)):
        # Penalty area, laid out for the +X end and mirrored: the front line's outer edge is
        # PENALTY_D from the goal line, the side lines run from it to the goal line.
        def x_span(a, b):
            return (a, b) if sign > 0 else (-b, -a)
        fx0, fx1 = x_span(hx - PENALTY_D, hx - PENALTY_D + LINE)
        sx0, sx1 = x_span(hx - PENALTY_D + LINE, hx - LINE)
        objects += [
            quad(f"penalty_{side}_front", "line", fx0, -PENALTY_W / 2, fx1, PENALTY_W / 2, LINE_Z),
            quad(f"penalty_{side}_side_a", "line", sx0, PENALTY_W / 2 - LINE, sx1, PENALTY_W / 2, LINE_Z),
            quad(f"penalty_{side}_side_b", "line", sx0, -PENALTY_W / 2, sx1, -PENALTY_W / 2 + LINE, LINE_Z),
        ]
        # Goal: back wall, two side walls and a crossbar behind the goal line.
        back = sign * (hx + GOAL_D)
        mid = sign * (hx + GOAL_D / 2)
        mat = "goal_" + side
        objects += [
            box(f"goal_{side}_back", mat, back + sign * GOAL_WALL / 2, 0, GOAL_H / 2, GOAL_WALL, GOAL_W, GOAL_H),
            box(f"goal_{side}_side_a", mat, mid, GOAL_W / 2 + GOAL_WALL / 2, GOAL_H / 2, GOAL_D, GOAL_WALL, GOAL_H),
            box(f"goal_{side}_side_b", mat, mid, -GOAL_W / 2 - GOAL_WALL / 2, GOAL_H / 2, GOAL_D, GOAL_WALL, GOAL_H),
            box(f"goal_{side}_crossbar", mat, mid, 0, GOAL_H + GOAL_WALL / 2, GOAL_D, GOAL_W + 2 * GOAL_WALL, GOAL_WALL),
        ]
    # Border wall on the carpet's edge (inner face at the carpet boundary).
    t = BORDER_T
    objects += [
        box("border_south", "border", 0, -cy - t / 2, BORDER_H / 2, 2 * cx + 2 * t, t, BORDER_H),
        box("border_north", "border", 0, cy + t / 2, BORDER_H / 2, 2 * cx + 2 * t, t, BORDER_H),
        box("border_west", "border", -cx - t / 2, 0, BORDER_H / 2, t, 2 * cy, BORDER_H),
        box("border_east", "border", cx + t / 2, 0, BORDER_H / 2, t, 2 * cy, BORDER_H),
    ]
    beacons = [  # (name, x, y, top colour, bottom colour)
        ("beacon_se", BEACON_X, -(hy + BEACON_OUT), "magenta", "yellow"),
        ("beacon_ne", BEACON_X, hy + BEACON_OUT, "yellow", "magenta"),
        ("beacon_sw", -BEACON_X, -(hy + BEACON_OUT), "magenta", "cyan"),
        ("beacon_nw", -BEACON_X, hy + BEACON_OUT, "cyan", "magenta"),
    ]
    landmarks = []
    r = BEACON_D / 2
    for name, x, y, top, bottom in beacons:
        objects += [
            {"name": name + "_white", "type": "cylinder", "material": "beacon_white",
             "base": [x, y, 0], "top": [x, y, 0.2], "radius": r},
            {"name": name + "_lower", "type": "cylinder", "material": bottom,
             "base": [x, y, 0.2], "top": [x, y, 0.3], "radius": r},
            {"name": name + "_upper", "type": "cylinder", "material": top,
             "base": [x, y, 0.3], "top": [x, y, BEACON_H], "radius": r},
        ]
        landmarks += [
            {"name": name + "_upper", "position": [x, y, 0.35], "diameter": BEACON_D, "height": 0.1,
             "colour_class": top},
            {"name": name + "_lower", "position": [x, y, 0.25], "diameter": BEACON_D, "height": 0.1,
             "colour_class": bottom},
        ]
    lights = [{"name": f"ceiling_{i}", "position": [sx * 1.8, sy * 1.2, 3.0], "intensity": 0.35}
              for i, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1)))]
    start = [hx, -hy, 180.0]
    loop = [[hx, -hy], [-hx, -hy], [-hx, hy], [hx, hy], [hx, -hy], [-hx, hy]]
    return {
        "format": "omnicam-scene/1",
        "name": "robocup2006",
        "description": "RoboCup 2006 Four-Legged League field (docs/scene-format.md). Origin at the field centre, "
                       "+X along the long axis toward the yellow goal, +Z up, floor at Z = 0, metres.",
        "comment": {
            "field_of_play_m": [FIELD_X, FIELD_Y], "carpet_margin_m": MARGIN, "line_width_m": LINE,
            "line_height_above_carpet_m": LINE_Z, "centre_circle_diameter_m": CENTRE_CIRCLE_D,
            "penalty_area_width_depth_m": [PENALTY_W, PENALTY_D],
            "goal_width_height_depth_m": [GOAL_W, GOAL_H, GOAL_D], "goal_wall_m": GOAL_WALL,
            "border_wall_height_thickness_m": [BORDER_H, BORDER_T],
            "beacon_diameter_height_m": [BEACON_D, BEACON_H],
            "beacon_layout": "white 0-0.20 m, lower band 0.20-0.30 m, upper band 0.30-0.40 m; centres at "
                             "x = ±1.35 m from the halfway line and 0.15 m outside the long edges",
            "lights": "four point lights 3 m above the field; each material: ambient 0.3, diffuse 0.7",
            "start_pose": "the field's lower-right corner (+X, −Y) heading along the first path segment",
        },
        "background": [0.0, 0.0, 0.0],
        "rig": {"height": 0.40, "mirror": {"k": 11.546, "c": 0.02321, "rim_elevation_deg": 45.0},
                "image": {"size": 360}},
        "start_pose": start,
        "materials": {
            "carpet": {"color": [0.06, 0.32, 0.08], "ambient": 0.3, "diffuse": 0.7, "class": "floor"},
            "line": {"color": [0.85, 0.85, 0.85], "ambient": 0.3, "diffuse": 0.7, "class": "line"},
            "border": {"color": [0.8, 0.8, 0.8], "ambient": 0.3, "diffuse": 0.7, "class": "wall"},
            "goal_yellow": {"color": [0.85, 0.7, 0.02], "ambient": 0.3, "diffuse": 0.7, "class": "goal"},
            "goal_blue": {"color": [0.2, 0.5, 0.9], "ambient": 0.3, "diffuse": 0.7, "class": "goal"},
            "beacon_white": {"color": [0.9, 0.9, 0.9], "ambient": 0.3, "diffuse": 0.7, "class": "beacon"},
            "magenta": {"color": [0.85, 0.02, 0.55], "ambient": 0.3, "diffuse": 0.7, "class": "beacon"},
            "yellow": {"color": [0.9, 0.8, 0.02], "ambient": 0.3, "diffuse": 0.7, "class": "beacon"},
            "cyan": {"color": [0.02, 0.65, 0.85], "ambient": 0.3, "diffuse": 0.7, "class": "beacon"},
        },
        "objects": objects,
        "lights": lights,
        "landmarks": landmarks,
        "paths": [{"name": "thesis-loop", "frames": 100, "waypoints": loop,
                   "comment": "thesis §4: from the lower-right corner clockwise (seen from above) along the "
                              "field edges back to the start, then diagonally toward the opposite corner; "
                              "100 poses evenly spaced by arc length, heading along the path"}],
    }


# ---------------------------------------------------------------- incidence-angle rings
RING_RADIUS = 1.0   # rings lie on an open cylinder of this radius around the viewpoint's axis
VIEWPOINT_Z = 0.40  # rig height: F' at (0, 0, 0.40)


def ring_half_width_deg(theta_deg):
    # Thin (0.26 px wide at 5°, 1.8 px at 135° in a 360 px image) and symmetric in θ: a band's
    # width biases a measured radius by about w²/(2r), negligible at this width.
    del theta_deg
    return 0.2


def incidence_rings():
    objects = []
    for theta in range(5, 140, 5):
        w = ring_half_width_deg(theta)
        # A direction at incidence θ (0 = straight down) meets the cylinder at
        # z = z_F' − R·cot θ; the band spans θ − w … θ + w.
        z_low = VIEWPOINT_Z - RING_RADIUS / math.tan(math.radians(theta - w))
        z_high = VIEWPOINT_Z - RING_RADIUS / math.tan(math.radians(theta + w))
        objects.append({"name": f"ring_{theta:03d}", "type": "cylinder",
                        "material": "red" if theta == 90 else "white",
                        "base": [0, 0, z_low], "top": [0, 0, z_high], "radius": RING_RADIUS, "caps": False})
    return {
        "format": "omnicam-scene/1",
        "name": "incidence-rings",
        "description": "Thin bright rings of equal incidence angle θ = 5°, 10°, …, 135° around the effective "
                       "viewpoint on a black background; the 90° ring is red (thesis Fig. 3.11).",
        "comment": {
            "geometry": "each ring is an open cylinder band of radius 1 m coaxial with the viewpoint; seen from "
                        "F' only directions matter, and cylinders are exact primitives in every engine",
            "band_half_width_deg": 0.2,
            "rig": "the mirror extends to 50° elevation while the image is framed at 45°, so the 135° ring "
                   "is whole inside the image (touching the border only at four points)",
        },
        "background": [0.0, 0.0, 0.0],
        "rig": {"height": VIEWPOINT_Z, "mirror": {"k": 11.546, "c": 0.02321, "rim_elevation_deg": 50.0},
                "image": {"size": 360, "framing_elevation_deg": 45.0}},
        "start_pose": [0.0, 0.0, 0.0],
        "materials": {"white": {"color": [1.0, 1.0, 1.0]}, "red": {"color": [1.0, 0.0, 0.0]}},
        "objects": objects,
    }


# ---------------------------------------------------------------- tiled room (thesis Figs. 3.13c–3.15c)
ROOM = 4.0            # square room, metres
TILE = 0.5            # floor tiles: a checkerboard of 0.5 m squares
WALL_H, STRIPE = 1.2, 0.2  # walls 1.2 m high with 0.2 m horizontal stripes
DOOR_AT, DOOR_W = 1.0, 0.3  # a dark vertical strip on each wall: vertical edges for the panorama


def tiled_room():
    h = ROOM / 2
    n = int(ROOM / TILE)
    objects = []
    for i in range(n):
        for j in range(n):
            objects.append(quad(f"tile_{i}_{j}", "tile_light" if (i + j) % 2 == 0 else "tile_dark",
                                -h + i * TILE, -h + j * TILE, -h + (i + 1) * TILE, -h + (j + 1) * TILE, 0.0))
    walls = [  # origin, edge along the wall (inner faces)
        ("south", [-h, -h], [ROOM, 0]), ("east", [h, -h], [0, ROOM]),
        ("north", [h, h], [-ROOM, 0]), ("west", [-h, h], [0, -ROOM]),
    ]
    for name, origin, edge in walls:
        # A dark vertical door strip, 1 mm in front of the wall, 1.0–1.3 m along it.
        inward = [-edge[1] / ROOM * 0.001, edge[0] / ROOM * 0.001]
        start = [origin[0] + edge[0] / ROOM * DOOR_AT + inward[0], origin[1] + edge[1] / ROOM * DOOR_AT + inward[1]]
        objects.append({"name": f"door_{name}", "type": "quad", "material": "door",
                        "origin": [start[0], start[1], 0.0],
                        "edge_u": [edge[0] / ROOM * DOOR_W, edge[1] / ROOM * DOOR_W, 0], "edge_v": [0, 0, WALL_H]})
        for k in range(int(WALL_H / STRIPE)):
            objects.append({"name": f"wall_{name}_{k}", "type": "quad",
                            "material": "stripe_light" if k % 2 == 0 else "stripe_dark",
                            "origin": [origin[0], origin[1], k * STRIPE], "edge_u": [edge[0], edge[1], 0],
                            "edge_v": [0, 0, STRIPE]})
    return {
        "format": "omnicam-scene/1",
        "name": "tiled-room",
        "description": "A square room with a checkerboard floor and horizontally striped walls (docs/scene-format.md, thesis "
                       "Figs. 3.13(c)–3.15(c)): straight floor lines must stay straight in the bird's-eye view, "
                       "vertical edges vertical in the panorama.",
        "comment": {"room_m": ROOM, "tile_m": TILE, "wall_height_m": WALL_H, "stripe_m": STRIPE,
                    "door_strip": "0.3 m wide, 1.0 m along each wall (counter-clockwise), 1 mm in front of it"},
        "start_pose": [0.0, 0.0, 0.0],
        "materials": {
            "tile_light": {"color": [0.8, 0.8, 0.8]}, "tile_dark": {"color": [0.15, 0.15, 0.15]},
            "stripe_light": {"color": [0.85, 0.6, 0.3]}, "stripe_dark": {"color": [0.2, 0.3, 0.6]},
            "door": {"color": [0.02, 0.02, 0.02]},
        },
        "objects": objects,
        "lights": [{"name": "ceiling", "position": [0.3, 0.2, 2.5], "intensity": 0.7}],
    }


if __name__ == "__main__":
    dump("robocup2006.json", robocup2006())
    dump("tiled-room.json", tiled_room())
    dump("incidence-rings.json", incidence_rings())
