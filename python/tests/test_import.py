"""visgrab.import_grasps, visgrab import and Grasp.jaw: graspnet and Contact-GraspNet files
written here with numpy (the formats' own writer), their grasps checked against the conventions
worked out independently with numpy (docs/grasp-format.md, "Importing grasps")."""
import numpy as np
import pytest

import visgrab

from conftest import cli

SCENE = "plain/single/cocacola/01"


@pytest.fixture(scope="module")
def franka():
    try:
        hand = visgrab.Hand("franka")
    except (ValueError, OSError) as e:
        pytest.skip(f"no franka hand in this tree: {e}")
    if hand.jaw_frame is None:
        pytest.skip("the franka hand declares no jaw frame in this tree")
    return hand


def camera_pose(db):
    """The rectified left camera in the table frame: X_table_left R1^T (docs/database-format.md)."""
    k = db.scene(SCENE).calibration
    x = np.array(k["X_table_left"], dtype=float)
    r1 = np.array(k["R1"], dtype=float)
    out = x.copy()
    out[:3, :3] = x[:3, :3] @ r1.T
    return out


def graspnet_rows():
    """Two GraspNet grasps: approach along the camera's z, closing along its x (columns of R:
    a, b, a x b), t 0.5 m in front of the camera; the second 0.1 m wide (wider than the stroke)."""
    a, b = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    r = np.column_stack([a, b, np.cross(a, b)])
    rows = []
    for width in (0.05, 0.1):
        rows.append(np.concatenate([[0.9, width, 0.02, 0.03], r.ravel(), [0.02, -0.01, 0.5],
                                    [1.0]]))
    return np.array(rows, dtype=np.float32)


def test_jaw_grasp_round_trip():
    g = visgrab.Grasp.jaw(scene=SCENE, method="net", id="0", position=[0.1, 0.2, 0.3],
                          quaternion=[0, 1, 0, 0], width=0.05, score=0.75)
    assert g.kind == "jaw"
    assert g.width == 0.05 and g.score == 0.75
    np.testing.assert_allclose(g.jaw_position, [0.1, 0.2, 0.3])
    # q = (0, 1, 0, 0): a half turn about x, so z points down.
    np.testing.assert_allclose(g.jaw_pose[:3, 2], [0, 0, -1], atol=1e-12)
    assert g.pose is None
    assert visgrab.Grasp.jaw(scene=SCENE, method="net", id="1", pose=np.eye(4),
                             width=0.01).score is None
    with pytest.raises(ValueError, match="width"):
        visgrab.Grasp.jaw(scene=SCENE, method="net", id="2", pose=np.eye(4), width=-0.01)


def test_graspnet_import_places_the_fingertips_at_t_plus_depth(db, franka, tmp_path):
    file = tmp_path / "grasps.npy"
    np.save(file, graspnet_rows())
    with pytest.warns(UserWarning, match=r"grasps.npy: grasp 1: width 0.1"):
        grasps = visgrab.import_grasps("graspnet", file, db=db, scene=SCENE, hand=franka)
    assert [g.id for g in grasps] == ["0"]
    g = grasps[0]
    assert g.method == "graspnet" and g.scene == SCENE
    assert g.score == pytest.approx(0.9, abs=1e-6)
    x_wc = camera_pose(db)
    tip = franka.jaw_frame["tip_depth"]
    # The fingertips' front, tip_depth beyond the pad centre along the jaw's z, is t + depth a.
    front = (g.jaw_pose @ [0, 0, tip, 1])[:3]
    np.testing.assert_allclose(front, (x_wc @ [0.02, -0.01, 0.53, 1])[:3], atol=1e-6)
    np.testing.assert_allclose(g.jaw_pose[:3, 2], x_wc[:3, 2], atol=1e-6)  # approach: camera z
    np.testing.assert_allclose(g.jaw_pose[:3, 0], x_wc[:3, 0], atol=1e-6)  # closing: camera x
    with pytest.raises(ValueError, match="grasp 1"):
        visgrab.import_grasps("graspnet", file, db=db, scene=SCENE, hand=franka, strict=True)
    with pytest.raises(ValueError, match="camera frame"):
        visgrab.import_grasps("graspnet", file, db=db, hand=franka)
    with pytest.raises(ValueError, match="unknown format"):
        visgrab.import_grasps("gpd", file, db=db, scene=SCENE, hand=franka)


def test_contact_graspnet_pickled_and_plain_give_the_same_grasps(db, franka, tmp_path):
    hand_pose = np.eye(4)
    hand_pose[:3, 3] = [0.0, 0.0, 0.4]
    pred = {2: np.array([hand_pose]), 5: np.array([hand_pose, hand_pose])}
    scores = {2: np.array([0.3]), 5: np.array([0.6, 0.7])}
    pickled = tmp_path / "predictions.npz"
    np.savez(pickled, pred_grasps_cam=pred, scores=scores, contact_pts={})
    plain = tmp_path / "plain.npz"
    np.savez(plain, grasps=np.concatenate(list(pred.values())),
             scores=np.concatenate(list(scores.values())))
    a = visgrab.import_grasps("contact-graspnet", pickled, db=db, scene=SCENE, hand=franka,
                              allow_pickle=True)
    b = visgrab.import_grasps("contact-graspnet", plain, db=db, scene=SCENE, hand=franka)
    assert [g.score for g in a] == pytest.approx([0.3, 0.6, 0.7])
    assert len(a) == len(b) == 3
    for ga, gb in zip(a, b):
        np.testing.assert_allclose(ga.jaw_pose, gb.jaw_pose)
    # The pad centre 0.1034 m along the hand's z: (0, 0, 0.5034) in the camera.
    np.testing.assert_allclose(a[0].jaw_position, (camera_pose(db) @ [0, 0, 0.5034, 1])[:3],
                               atol=1e-9)
    assert a[0].width == 0.08
    # Unpickling is the user's explicit choice: by default (as numpy's load) it is refused.
    with pytest.raises(ValueError, match="refused by default.*allow_pickle=True.*trusted files"):
        visgrab.import_grasps("contact-graspnet", pickled, db=db, scene=SCENE, hand=franka)
    with pytest.raises(ValueError, match="trusted files only"):
        visgrab.import_grasps("contact-graspnet", pickled, db=db, scene=SCENE, hand=franka,
                              allow_pickle=False)


def test_cli_import_writes_the_grasp_list_and_exits_1_when_all_are_rejected(db, franka,
                                                                              test_db_path,
                                                                              binary, tmp_path):
    file = tmp_path / "grasps.npy"
    np.save(file, graspnet_rows())
    out = tmp_path / "grasps.csv"
    result = cli(binary, "import", "graspnet", file, "--db", test_db_path, "--scene", SCENE,
                 "--out", out, "--method", "gn")
    assert "1 grasps imported, 1 rejected" in result.stdout
    assert f"{file}: grasp 1: width 0.1 m is more than hand" in result.stderr
    read = visgrab.read_grasps(out)
    assert [(g.id, g.method) for g in read] == [("0", "gn")]
    np.save(file, graspnet_rows()[1:])
    rejected = cli(binary, "import", "graspnet", file, "--db", test_db_path, "--scene", SCENE,
                   "--out", out, check=False)
    assert rejected.returncode == 1, rejected.stdout + rejected.stderr
    assert "0 grasps imported, 1 rejected" in rejected.stdout
    usage = cli(binary, "import", "graspnet", file, "--db", test_db_path, "--out", out,
                check=False)
    assert usage.returncode == 2
    assert "--scene" in usage.stderr
    pickled = tmp_path / "predictions.npz"
    np.savez(pickled, pred_grasps_cam={1: np.array([np.eye(4)])}, scores={1: np.array([0.5])})
    refused = cli(binary, "import", "contact-graspnet", pickled, "--db", test_db_path, "--scene",
                  SCENE, "--out", out, check=False)
    assert refused.returncode == 1
    assert "np.savez(\"grasps.npz\", grasps=np.concatenate(list(pred_grasps_cam.values()))" \
        in refused.stderr


def test_top_down_graspnet_and_contact_graspnet_grasps_hold_a_standing_box(db, franka, tmp_path):
    """By physics: a top-down grasp across the narrow side of the standing salt box (4.5 cm of
    the Franka's 8 cm), made from its ground-truth pose and written in each format's camera-frame
    convention, holds through the paper's lift (Franka 70 N, mu 0.6: 84 N against 5.2 N)."""
    from conftest import trials_rows
    scene = "plain/single/saltbox/01"
    X_wo = np.array(db.scene(scene).ground_truth[0]["pose"], dtype=float)
    X_cw = np.linalg.inv(np.array(db.scene(scene).cloud_frame, dtype=float))  # camera <- table
    # The jaw frame in the table frame: 2 cm below the box's top (12.5 cm) on its axis, z down,
    # x across the 4.5 cm side (the box frame's x).
    centre = (X_wo @ [0.0, 0.0, 0.105, 1.0])[:3]
    approach, closing = np.array([0.0, 0.0, -1.0]), X_wo[:3, 0]
    closing = closing - (closing @ approach) * approach
    closing /= np.linalg.norm(closing)
    to_cam = lambda v: X_cw[:3, :3] @ v
    c_cam = (X_cw @ np.r_[centre, 1.0])[:3]
    a_cam, b_cam = to_cam(approach), to_cam(closing)
    # GraspNet: columns approach, closing, their cross; fingertips' front at t + depth a; the pad
    # centre tipDepth behind it.
    depth, tip = 0.02, franka.jaw_frame["tip_depth"]
    t = c_cam - (depth - tip) * a_cam
    row = np.r_[0.9, 0.055, 0.02, depth, np.column_stack([a_cam, b_cam, np.cross(a_cam, b_cam)])
                .ravel(), t, 13.0]
    np.save(tmp_path / "gn.npy", row.reshape(1, 17).astype(np.float64))
    # Contact-GraspNet: the Panda hand's base frame (z approach, x closing), 0.1034 m behind the
    # pads' centre.
    hand = np.eye(4)
    hand[:3, :3] = np.column_stack([b_cam, np.cross(a_cam, b_cam), a_cam])
    hand[:3, 3] = c_cam - 0.1034 * a_cam
    np.savez(tmp_path / "cgn.npz", grasps=hand.reshape(1, 4, 4), scores=np.array([0.8]))
    grasps = (visgrab.import_grasps("graspnet", tmp_path / "gn.npy", db, scene=scene,
                                    method="graspnet", strict=True) +
              visgrab.import_grasps("contact-graspnet", tmp_path / "cgn.npz", db, scene=scene,
                                    method="contact-graspnet", strict=True))
    for g in grasps:
        np.testing.assert_allclose(g.jaw_position, centre, atol=1e-6)
    visgrab.run(db, grasps, hand="franka", threads=1, out=tmp_path / "results")
    outcomes = {r["method"]: r["outcome"] for r in trials_rows(tmp_path / "results/trials.csv")}
    assert outcomes == {"graspnet": "stable", "contact-graspnet": "stable"}, outcomes
