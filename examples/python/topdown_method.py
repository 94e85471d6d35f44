#!/usr/bin/env python3
"""A grasp method of its own: top-down SDH grasps at the clusters of the cloud above the table.
Usage: topdown_method.py DATABASE SCENES_FILTER OUT  (writes OUT/results and OUT/report)"""
import sys
import numpy as np
import visgrab

DOWN = [0.0, 0.0, 1.0, 0.0]  # 180 degrees about y: the hand's approach axis points down


def clusters(points, radius=0.04, most=3, least=100):
    """Up to `most` clusters (>= `least` points within `radius`), highest first: centre, top."""
    centres = []
    for p in points[np.argsort(-points[:, 2])]:
        near = points[np.hypot(*(points[:, :2] - p[:2]).T) < radius]
        if len(near) >= least and all(np.hypot(*(p[:2] - c[:2])) > 2 * radius for c in centres):
            centres.append(np.r_[near[:, :2].mean(axis=0), np.median(near[:, 2])])
        if len(centres) == most:
            return centres
    return centres


def main(db_path, scenes, out):
    db, grasps = visgrab.Database(db_path), []
    for sid in db.scene_ids(scenes):
        cloud = db.scene(sid).point_cloud(frame="table")[:, :3]
        above = cloud[(cloud[:, 2] > 0.01) & (np.abs(cloud[:, :2]).max(axis=1) < 0.2)]
        for i, c in enumerate(clusters(above)):
            for depth, shape in ((0.02, "SDH_BALL"), (0.04, "SDH_CYL")):
                grasps.append(visgrab.Grasp.preshape(
                    scene=sid, method="topdown", id=f"c{i}-{shape}", preshape=shape,
                    position=[c[0], c[1], c[2] - depth], quaternion=DOWN))
    trials = visgrab.run(db, grasps, hand="sdh", threads=2, out=f"{out}/results")
    print(f"{len(trials)} trials:", trials.summary["outcomes"])
    print("report:", visgrab.analyze([f"{out}/results"], out=f"{out}/report", pictures=False))


if __name__ == "__main__":
    main(*sys.argv[1:4]) if len(sys.argv) == 4 else sys.exit(__doc__)
