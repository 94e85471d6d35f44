#!/usr/bin/env python3
"""A method as today's methods work: grasps from the depth image and the camera's intrinsics,
in GraspNet's .npy layout in the camera frame, imported and run with the Franka Hand.
Usage: graspnet_style_method.py DATABASE SCENES_FILTER OUT  (writes OUT/*.npy, OUT/results)"""
import os
import sys
import numpy as np
import visgrab


def grasp_rows(depth, mask, P1, stroke=0.08):
    """One GraspNet row per object seen: at its centroid, approaching along the line of sight,
    closing across its narrowest extent (score, width, height, depth, R row-major, t, id)."""
    v, u = np.nonzero(depth > 0)
    z = depth[v, u]
    points = np.c_[(u - P1[0, 2]) * z / P1[0, 0], (v - P1[1, 2]) * z / P1[1, 1], z]
    rows = []
    for obj in sorted(set(mask[v, u]) - {0, 255}):  # the instance mask's objects
        p = points[mask[v, u] == obj]
        c = p.mean(axis=0)
        x = c / np.linalg.norm(c)  # approach: from the camera through the centroid
        flat = (p - c) - np.outer((p - c) @ x, x)  # the points seen along the approach
        _, _, axes = np.linalg.svd(flat, full_matrices=False)
        y = axes[1] - (axes[1] @ x) * x  # closing: the narrowest spread across the approach
        y /= np.linalg.norm(y)
        width = np.ptp(flat @ y) + 0.01
        if width > stroke:
            continue
        R = np.c_[x, y, np.cross(x, y)]  # GraspNet: columns approach, closing, their cross
        rows.append([1.0, width, 0.02, 0.02, *R.ravel(), *c, obj])
    return np.array(rows, dtype=np.float32).reshape(-1, 17)


def main(db_path, scenes, out):
    db, grasps = visgrab.Database(db_path), []
    os.makedirs(out, exist_ok=True)
    for sid in db.scene_ids(scenes):
        scene = db.scene(sid)
        rows = grasp_rows(scene.depth, scene.mask, scene.calibration["P1"])
        file = os.path.join(out, sid.replace("/", "_") + ".npy")
        np.save(file, rows)  # what a GraspNet-style method hands over
        grasps += visgrab.import_grasps("graspnet", file, db, scene=sid, hand="franka",
                                        method="graspnet-style")
    trials = visgrab.run(db, grasps, hand="franka", threads=2, out=f"{out}/results")
    print(f"{len(trials)} trials:", trials.summary["outcomes"])


if __name__ == "__main__":
    main(*sys.argv[1:4]) if len(sys.argv) == 4 else sys.exit(__doc__)
