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
    assert result.returncode == 1 and "trials.csv" in result.stderr
