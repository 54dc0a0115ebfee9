#!/usr/bin/env python3
"""Loads a benchmark config, checks a path and prints the clearances along it.

Usage: check_path.py [CONFIG.cfg] [WAYPOINTS]

The path is the straight line from the config's start to its goal, cut into
WAYPOINTS - 1 edges (default 8). Each edge is checked exactly under OMPL's
interpolation (mddual's motion check: the first contact fraction, exact for
translation edges); at each waypoint the script prints how far the robot can
translate along the edge's direction before it touches the world (directed
clearance). Exit status: 0 when the path is free, 1 when some edge collides,
2 on bad input.
"""
import pathlib
import sys

import numpy as np

import mddual


def main(argv):
    root = pathlib.Path(__file__).resolve().parents[2]
    cfg = argv[1] if len(argv) > 1 else str(root / "configs" / "thin_walls" / "thin_walls.cfg")
    waypoints = int(argv[2]) if len(argv) > 2 else 8
    if waypoints < 2:
        print("check_path.py: WAYPOINTS must be at least 2", file=sys.stderr)
        return 2
    try:
        scene = mddual.Scene.load(cfg)
    except mddual.Error as e:
        print(f"check_path.py: {e}", file=sys.stderr)
        return 2
    start = np.asarray(scene.start_state, float)
    goal = np.asarray(scene.goal_state, float)
    states = np.linspace(start, goal, waypoints)
    edges = scene.check_edges(states[:-1], states[1:])
    print(f"{cfg}: {scene.space}, {waypoints - 1} edges from start to goal")
    free = True
    for k in range(waypoints - 1):
        X_WR = scene.pose(states[k])
        step = scene.pose(states[k + 1])[:3, 3] - X_WR[:3, 3]
        clearance = float("inf")
        if np.linalg.norm(step) > 0.0:
            clearance = float(scene.directed_clearance(X_WR, step)["distance"][0])
        collides = bool(edges["collides"][k])
        free = free and not collides
        fraction = float(edges["fraction"][k])
        print(f"  edge {k}: {'collides at fraction %.6g' % fraction if collides else 'free'}; "
              f"clearance ahead {clearance:.6g} (edge length {np.linalg.norm(step):.6g})")
    print("path: " + ("free" if free else "in collision"))
    return 0 if free else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
