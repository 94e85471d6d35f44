"""examples/python end to end on a few scenes of the shared test database."""
import os
import subprocess
import sys

import pytest

from conftest import trials_rows


def run_example(source_dir, name, *args, cwd):
    result = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / name),
                             *map(str, args)], capture_output=True, text=True, cwd=cwd,
                            env=os.environ)
    return result


def test_topdown_method_and_figure7(source_dir, test_db_path, tmp_path):
    lines = len((source_dir / "examples/python/topdown_method.py").read_text().splitlines())
    assert lines < 40
    scenes = "plain/single/cocacola/01;textured/double/tomato_waterjug/04"
    result = run_example(source_dir, "topdown_method.py", test_db_path, scenes, tmp_path / "out",
                         cwd=tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    rows = trials_rows(tmp_path / "out/results/trials.csv")
    # Two grasps (SDH_BALL, SDH_CYL) per cluster, 1 to 3 clusters per scene; the summary line
    # counts them.
    for scene in scenes.split(";"):
        ids = [r["grasp"] for r in rows if r["scene"] == scene]
        assert len(ids) in (2, 4, 6) and sorted(ids)[:2] == ["c0-SDH_BALL", "c0-SDH_CYL"], ids
    assert {r["method"] for r in rows} == {"topdown"}
    assert result.stdout.startswith(f"{len(rows)} trials: {{")
    assert (tmp_path / "out/report/report.html").is_file()
    assert (tmp_path / "out/report/attempts.csv").is_file()

    pytest.importorskip("matplotlib", reason="python3-matplotlib is not installed")
    for source in (tmp_path / "out/report", tmp_path / "out/results"):
        png = tmp_path / f"figure7-{source.name}.png"
        result = run_example(source_dir, "figure7.py", source, png, cwd=tmp_path)
        assert result.returncode == 0, result.stdout + result.stderr
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10000
    result = run_example(source_dir, "figure7.py", tmp_path / "nothing", tmp_path / "x.png",
                         cwd=tmp_path)
    assert result.returncode == 1 and "nothing: error: no such result folder" in result.stderr


def test_graspnet_style_method(source_dir, test_db_path, tmp_path):
    lines = len((source_dir / "examples/python/graspnet_style_method.py").read_text().splitlines())
    assert lines < 60
    import numpy as np
    import visgrab
    scene = "plain/single/cocacola/01"
    result = run_example(source_dir, "graspnet_style_method.py", test_db_path, scene,
                         tmp_path / "out", cwd=tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    # One GraspNet row for the one object the mask shows, in the camera frame.
    rows = np.load(tmp_path / "out" / (scene.replace("/", "_") + ".npy"))
    assert rows.shape == (1, 17) and rows[0, 16] == 5  # object id 5: cocacola
    R = rows[0, 4:13].reshape(3, 3)
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-5)
    trials = trials_rows(tmp_path / "out/results/trials.csv")
    assert [(r["method"], r["grasp"]) for r in trials] == [("graspnet-style", "0")]
    # The jaw centre is where the row says, in the table frame: the fingertips' front centre
    # t + depth x, then 8.9 mm (the Franka's tipDepth) back along the approach; t is the
    # centroid of the can's visible points, so the centre lies within the can's radius of its
    # true axis (ground truth), and at most 5 cm over the table.
    db = visgrab.Database(str(test_db_path))
    grasp, = visgrab.import_grasps("graspnet", tmp_path / "out" / (scene.replace("/", "_") + ".npy"),
                                   db, scene=scene)
    X_tc = db.scene(scene).cloud_frame
    x, t, depth = R[:, 0], rows[0, 13:16], rows[0, 3]
    expected = (X_tc @ np.r_[t + (depth - 0.0089) * x, 1.0])[:3]
    assert np.allclose(grasp.jaw_position, expected, atol=1e-5)
    axis = db.scene(scene).ground_truth[0]["pose"][:3, 3]
    assert np.hypot(*(grasp.jaw_position[:2] - axis[:2])) < 0.034
    assert 0.0 < grasp.jaw_position[2] < 0.13
