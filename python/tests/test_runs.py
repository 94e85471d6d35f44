"""visgrab.run, read_results and analyze against `visgrab run` and `visgrab analyze` on the same
grasps (written with write_grasps): byte-identical trials.csv through either path, whatever the
thread count; the CLI's messages for rejected grasps; Ctrl-C and resume."""
import filecmp
import os
import re
import subprocess
import sys
import tempfile
import textwrap

import numpy as np
import pytest

import visgrab
from conftest import cli, trials_rows

SCENES = ["plain/single/cocacola/01", "plain/single/saltbox/01"]
DOWN = [0.0, 0.0, 1.0, 0.0]


def make_grasps(db):
    """Two grasps per scene: top-down at the object (it may hold) and high above it (missed)."""
    grasps = []
    for sid in SCENES:
        p = db.scene(sid).ground_truth[0]["pose"][:3, 3]
        grasps.append(visgrab.Grasp.preshape(scene=sid, method="py", id="at", preshape="SDH_CYL",
                                             position=[p[0], p[1], p[2] + 0.1],
                                             quaternion=DOWN))
        grasps.append(visgrab.Grasp.preshape(scene=sid, method="py", id="above",
                                             preshape="SDH_BALL",
                                             position=[p[0], p[1], p[2] + 0.4], quaternion=DOWN))
    return grasps


@pytest.fixture(scope="module")
def runs(db, binary, test_db_path, tmp_path_factory):
    """The same grasps through the module (1 thread) and the CLI (2 threads)."""
    root = tmp_path_factory.mktemp("runs")
    grasps = make_grasps(db)
    module_out = root / "module" / "results"
    trials = visgrab.run(db, grasps, hand="sdh", threads=1, out=module_out)
    grasp_file = root / "grasps.csv"
    visgrab.write_grasps(grasp_file, grasps)
    cli_out = root / "cli" / "results"
    cli(binary, "run", "--db", test_db_path, "--grasps", grasp_file, "--out", cli_out,
        "--threads", "2", "--quiet")
    return dict(root=root, grasps=grasps, trials=trials, module=module_out, cli=cli_out,
                grasp_file=grasp_file)


def test_trials_csv_is_byte_identical_to_the_cli(runs):
    module_bytes = (runs["module"] / "trials.csv").read_bytes()
    assert module_bytes == (runs["cli"] / "trials.csv").read_bytes()
    rows = trials_rows(runs["cli"] / "trials.csv")
    trials = runs["trials"]
    assert len(trials) == len(rows) == 4
    # The returned TrialResults are the CLI's rows (canonical order), field by field.
    assert [t.scene for t in trials] == [SCENES[0]] * 2 + [SCENES[1]] * 2
    for t, row in zip(trials, rows):
        assert (t.scene, t.method, t.id, str(t.rank)) == (row["scene"], row["method"],
                                                          row["grasp"], row["rank"])
        assert t.outcome == row["outcome"] and str(t.robwork_code) == row["robwork_code"]
        for name in ("q_lift", "q_gws", "q_gws_unit", "simulated_time"):
            assert getattr(t, name) == pytest.approx(float(row[name]), rel=1e-12, abs=0), name
        assert str(t.object) == row["object"] and t.detail == row["detail"]
        assert t.closing_capped is (row["closing_capped"] == "1")
    # Every column of trials.csv is a property of TrialResult (one definition drives both; the
    # grasp column is `id`).
    for column in rows[0]:
        assert hasattr(trials[0], "id" if column == "grasp" else column), column
    # The grasp 0.4 m above the object closes on nothing.
    assert [t.outcome for t in trials if t.id == "above"] == ["missed", "missed"]
    assert trials.summary["trials"] == 4 and trials.rejected == []
    assert sum(trials.summary["outcomes"].values()) == 4
    # The run's grasp list is kept where run.csv points (visgrab render --results uses it).
    assert trials.results.sources["grasps"] == [str(runs["module"] / "grasp_list.csv")]
    assert visgrab.read_grasps(runs["module"] / "grasp_list.csv") == runs["grasps"]


def test_two_threads_give_the_same_bytes_and_out_none_leaves_nothing(runs, db, tmp_path,
                                                                      monkeypatch):
    out = tmp_path / "two"
    visgrab.run(db.path, runs["grasps"], hand=visgrab.Hand("sdh"), threads=2, out=out)
    assert (out / "trials.csv").read_bytes() == (runs["module"] / "trials.csv").read_bytes()
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    trials = visgrab.run(db, runs["grasps"], threads=2, scenes=SCENES[1])
    assert os.listdir(scratch) == []
    expected = [t for t in runs["trials"] if t.scene == SCENES[1]]
    assert [(t.id, t.outcome, t.q_lift) for t in trials] == \
        [(t.id, t.outcome, t.q_lift) for t in expected]


def test_read_results_is_the_run(runs):
    results = visgrab.read_results(runs["cli"])
    assert results.scenes == visgrab.read_results(runs["module"]).scenes
    assert results.methods == ["py"] and results.label == "results"
    assert len(results) == 4 and [t.id for t in results] == [t.id for t in runs["trials"]]
    assert results[-1].id == runs["trials"][3].id
    assert "visgrab.Results('results', 4 trials" in repr(results)
    assert repr(results[0]).startswith("visgrab.TrialResult(scene=")


def test_rejected_grasps_have_the_cli_messages(runs, db, binary, test_db_path, tmp_path):
    good = runs["grasps"][1]
    bad = [
        visgrab.Grasp.preshape(scene=SCENES[0], method="py", id="shape", preshape="SDH_NONE",
                               position=[0, 0, 0.5], quaternion=DOWN),
        visgrab.Grasp.preshape(scene="plain/single/cocacola/99", method="py", id="where",
                               preshape="SDH_CYL", position=[0, 0, 0.5], quaternion=DOWN),
        visgrab.Grasp.pose_q(scene=SCENES[0], method="py", id="q", q=[0.0] * 6,
                             position=[0, 0, 0.5], quaternion=DOWN),
    ]
    out = tmp_path / "lenient"
    trials = visgrab.run(db, [good] + bad, threads=1, out=out, strict=False)
    assert [t.id for t in trials] == ["above"]
    assert len(trials.rejected) == 3
    # The CLI on the same grasp file prints the same diagnostics (file:line: error: ...).
    result = cli(binary, "run", "--db", test_db_path, "--grasps", out / "grasp_list.csv", "--out",
                 tmp_path / "cli", "--threads", "1", "--quiet")
    printed = [line for line in result.stderr.splitlines() if ": error: " in line]
    assert sorted(printed) == sorted(trials.rejected)
    assert any('unknown pre-shape "SDH_NONE" for hand "SchunkHand"' in m for m in printed)
    assert any('unknown scene "plain/single/cocacola/99"' in m for m in printed)
    # strict=True (the default) raises them before anything runs.
    for grasp in bad:
        strict_out = tmp_path / f"strict-{grasp.id}"
        with pytest.raises(ValueError) as error:
            visgrab.run(db, [good, grasp], threads=1, out=strict_out)
        message = str(error.value)
        assert message.startswith(f"{strict_out / 'grasp_list.csv'}:")
        # The same message but for the file's folder and line.
        unplaced = lambda text: re.sub(r"\S*grasp_list\.csv:\d+:", "FILE:", text)
        assert unplaced(message) in [unplaced(m) for m in trials.rejected], message
        assert not (strict_out / "trials.csv").exists()


def test_existing_results_need_resume_and_resume_completes(runs, db, tmp_path):
    kept = (runs["module"] / "grasp_list.csv").read_bytes()
    with pytest.raises(RuntimeError, match=r"trials\.csv already holds results; resume them "
                                           r"\(resume=True\)"):
        visgrab.run(db, runs["grasps"][:1], threads=1, out=runs["module"])
    assert (runs["module"] / "grasp_list.csv").read_bytes() == kept
    again = visgrab.run(db, runs["grasps"], threads=2, out=runs["module"], resume=True)
    assert again.summary["resumed"] == 4 and again.summary["trials"] == 0


def test_ctrl_c_stops_the_run_and_resume_gives_the_same_file(db, test_db_path, tmp_path):
    # 20 grasps (about 80 ms each): SIGINT arrives after the first progress report (the run
    # looks at Python's signals every 100 ms), the running trial finishes and the run stops.
    grasps = []
    for sid in SCENES:
        p = db.scene(sid).ground_truth[0]["pose"][:3, 3]
        grasps += [visgrab.Grasp.preshape(scene=sid, method="py", id=f"g{i}", preshape="SDH_CYL",
                                          position=[p[0] + 0.004 * i, p[1], p[2] + 0.1],
                                          quaternion=DOWN) for i in range(10)]
    grasp_file = tmp_path / "grasps.csv"
    visgrab.write_grasps(grasp_file, grasps)
    out = tmp_path / "stopped"
    script = textwrap.dedent(f"""
        import os, signal, visgrab
        grasps = visgrab.read_grasps({str(grasp_file)!r})
        def progress(done, total):
            os.kill(os.getpid(), signal.SIGINT)
        try:
            visgrab.run({str(test_db_path)!r}, grasps, threads=1, out={str(out)!r},
                        progress=progress)
        except KeyboardInterrupt:
            print("interrupted")
        """)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            env=os.environ)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "interrupted"
    done = trials_rows(out / "trials.csv")
    assert 1 <= len(done) < 20
    # The stopped run says it is unfinished: read with a warning, refused by analyze unless
    # allow_unfinished=True, whose report says so.
    with pytest.warns(UserWarning, match=r"unfinished\.txt: warning: the run has not finished"):
        partial = visgrab.read_results(out)
    assert not partial.finished and len(partial) == len(done)
    with pytest.raises(ValueError, match=r"the run has not finished .* --resume finishes it, "
                                         r"allow_unfinished=True uses the trials it has"):
        visgrab.analyze([out], out=tmp_path / "refused", pictures=False)
    assert not (tmp_path / "refused" / "report.md").exists()
    with pytest.warns(UserWarning, match="the run has not finished"):
        visgrab.analyze([out], out=tmp_path / "partial", pictures=False, allow_unfinished=True)
    assert '**Unfinished: run "stopped" has not finished' in (
        tmp_path / "partial" / "report.md").read_text()
    resumed = visgrab.run(test_db_path, grasps, threads=2, out=out, resume=True)
    assert resumed.summary["resumed"] == len(done)
    assert visgrab.read_results(out).finished and not (out / "unfinished.txt").exists()
    whole = tmp_path / "whole"
    visgrab.run(test_db_path, grasps, threads=1, out=whole)
    assert (out / "trials.csv").read_bytes() == (whole / "trials.csv").read_bytes()


def test_progress_callback_errors_stop_the_run(runs, db, tmp_path):
    def progress(done, total):
        raise ZeroDivisionError("from the callback")
    with pytest.raises(ZeroDivisionError, match="from the callback"):
        visgrab.run(db, runs["grasps"], threads=1, out=tmp_path / "cb", progress=progress)


def test_read_results_errors(tmp_path):
    with pytest.raises(OSError, match="trials.csv"):
        visgrab.read_results(tmp_path)
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "trials.csv").write_text("scene,method\nnonsense\n")
    with pytest.raises(OSError, match=r"trials\.csv:\d+"):
        visgrab.read_results(broken)


def test_analyze_writes_the_cli_report(runs, binary, tmp_path):
    cli(binary, "analyze", runs["cli"], "--out", tmp_path / "cli-report", "--no-pictures",
        "--quiet")
    report = visgrab.analyze([runs["cli"]], out=tmp_path / "py-report", pictures=False)
    assert report == str(tmp_path / "py-report" / "report.html")
    names = sorted(os.listdir(tmp_path / "cli-report"))
    assert names == sorted(os.listdir(tmp_path / "py-report"))
    assert {"report.html", "report.md", "attempts.csv"} <= set(names)
    match, mismatch, errors = filecmp.cmpfiles(tmp_path / "cli-report", tmp_path / "py-report",
                                               [n for n in names if os.path.isfile(
                                                   tmp_path / "cli-report" / n)], shallow=False)
    assert mismatch == [] and errors == []
    with pytest.raises(OSError):
        visgrab.analyze([tmp_path / "none"], out=tmp_path / "x", pictures=False)


def test_analyze_takes_the_clis_interval_options(runs, binary, tmp_path):
    """ci_level, bootstrap and seed are --ci-level, --bootstrap and --seed: the same files with
    any thread count; bootstrap=0 leaves the intervals, success.csv and comparisons.csv out."""
    dirs = [runs["cli"], runs["module"]]
    cli(binary, "analyze", *dirs, "--out", tmp_path / "cli", "--no-pictures", "--quiet",
        "--ci-level", "0.9", "--bootstrap", "300", "--seed", "7", "--threads", "2")
    visgrab.analyze(dirs, out=tmp_path / "py", pictures=False, ci_level=0.9, bootstrap=300,
                    seed=7, threads=1)
    names = sorted(os.listdir(tmp_path / "cli"))
    assert {"success.csv", "comparisons.csv"} <= set(names)
    assert names == sorted(os.listdir(tmp_path / "py"))
    _, mismatch, errors = filecmp.cmpfiles(tmp_path / "cli", tmp_path / "py", names,
                                           shallow=False)
    assert mismatch == [] and errors == []
    report = (tmp_path / "py" / "report.md").read_text()
    assert "Intervals: 90 % percentile intervals of a scene bootstrap (300 resamples, seed 7)" \
        in report
    # The two runs ran the same grasps: their comparison differs by nothing.
    header, *rows = (tmp_path / "py" / "comparisons.csv").read_text().splitlines()
    assert header.startswith("group,method_a,method_b,scenes,rate_a,rate_b,difference,")
    overall = [r for r in rows if r.startswith("overall,")]
    assert len(overall) == 1 and ",0,0,0,1," in overall[0]

    visgrab.analyze(dirs, out=tmp_path / "none", pictures=False, bootstrap=0)
    assert not (tmp_path / "none" / "success.csv").exists()
    assert "_ci_low" not in (tmp_path / "none" / "quality.csv").read_text()
    for bad in (dict(ci_level=1.5), dict(bootstrap=-1), dict(seed=-3)):
        with pytest.raises(ValueError):
            visgrab.analyze(dirs, out=tmp_path / "bad", pictures=False, **bad)
    # The messages name the Python argument and the value as given (the CLI's one check).
    with pytest.raises(ValueError) as e:
        visgrab.analyze(dirs, out=tmp_path / "bad", pictures=False, ci_level=1.5)
    assert str(e.value) == "ci_level must be between 0 and 1 (exclusive), got 1.5"
    for few in (1, 2, 99):
        with pytest.raises(ValueError) as e:
            visgrab.analyze(dirs, out=tmp_path / "bad", pictures=False, bootstrap=few)
        assert str(e.value).startswith(
            f"bootstrap must be 0 (no intervals) or at least 100, got {few} ("), str(e.value)
        bad = cli(binary, "analyze", *dirs, "--out", tmp_path / "bad", "--no-pictures",
                  "--quiet", "--bootstrap", str(few), check=False)
        assert bad.returncode == 2 and \
            f"--bootstrap: must be 0 (no intervals) or at least 100, got {few} (" in bad.stderr
    for option, value in (("--ci-level", "1.5"), ("--bootstrap", "-1"), ("--seed", "x")):
        bad = cli(binary, "analyze", *dirs, "--out", tmp_path / "bad", "--no-pictures",
                  "--quiet", option, value, check=False)
        assert bad.returncode == 2 and option in bad.stderr, (option, bad.stderr)


def test_analyze_tells_folders_of_the_same_name_apart(runs, tmp_path):
    """root/cli/results and root/module/results (both named results) are labelled cli/results
    and module/results, as the CLI labels them; one folder given twice is refused."""
    visgrab.analyze([runs["cli"], runs["module"]], out=tmp_path / "r", pictures=False)
    header, *rows = (tmp_path / "r" / "comparisons.csv").read_text().splitlines()
    overall = [r for r in rows if r.startswith("overall,")]
    assert len(overall) == 1 and overall[0].startswith("overall,cli/results: py,module/results: py,")
    with pytest.raises(ValueError, match="is given twice"):
        visgrab.analyze([runs["cli"], runs["cli"]], out=tmp_path / "twice", pictures=False)
    # A run alone keeps its folder's name.
    visgrab.analyze([runs["cli"]], out=tmp_path / "alone", pictures=False, bootstrap=0)
    assert "results: py" not in (tmp_path / "alone" / "report.md").read_text()


def test_run_option_errors_use_the_python_names(db, runs):
    """An adaptive rule that could never stop a grasp with this many repeats names repeats=,
    not the CLI's --repeats."""
    with pytest.raises(ValueError) as e:
        visgrab.run(db, runs["grasps"], repeats=2, adaptive=True)
    assert str(e.value).startswith("adaptive: the adaptive rule (alpha 0.05, margin 0.65)")
    assert "repeats=2 it never stops" in str(e.value) and "--repeats" not in str(e.value)
    for bad in (0, 10001):
        with pytest.raises(ValueError, match=f"repeats must be between 1 and 10000, got {bad}"):
            visgrab.run(db, runs["grasps"], repeats=bad)


def test_repeats_run_as_the_cli_runs_them(runs, binary, test_db_path, tmp_path):
    """repeats=3 through the module equals `visgrab run --repeats 3` byte for byte; repeat 0 is
    the plain trial; every trial says its repeat and seed; grasps.csv is written."""
    out = tmp_path / "module"
    trials = visgrab.run(visgrab.Database(test_db_path), runs["grasps"], threads=2, out=out,
                         repeats=3)
    assert len(trials) == 3 * len(runs["trials"])
    assert sorted({t.repeat for t in trials}) == [0, 1, 2]
    assert all((t.seed == 0) == (t.repeat == 0) for t in trials)
    plain = {(t.scene, t.id): (t.outcome, t.q_lift, t.simulated_time) for t in runs["trials"]}
    for t in trials:
        if t.repeat == 0:
            assert (t.outcome, t.q_lift, t.simulated_time) == plain[(t.scene, t.id)]
    cli(binary, "run", "--db", test_db_path, "--grasps", out / "grasp_list.csv", "--out",
        tmp_path / "cli", "--threads", "1", "--repeats", "3", "--quiet")
    for name in ("trials.csv", "grasps.csv"):
        assert (out / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    header = (out / "grasps.csv").read_text().splitlines()[0]
    assert header.startswith("scene,method,grasp,rank,repeats,held,p,p_ci_low,p_ci_high,")
    with pytest.raises(ValueError, match="needs repeats"):
        visgrab.run(visgrab.Database(test_db_path), runs["grasps"], out=tmp_path / "x",
                    noise=tmp_path / "none.xml")
    with pytest.raises(TypeError, match="repeats must be an int"):
        visgrab.run(visgrab.Database(test_db_path), runs["grasps"], out=tmp_path / "z",
                    repeats=2.5)
    bad = tmp_path / "bad.xml"
    bad.write_text("<NoiseModel>\n  <Mass sigma=\"-1\"/>\n</NoiseModel>\n")
    with pytest.raises(OSError, match=r"bad\.xml:2"):
        visgrab.run(visgrab.Database(test_db_path), runs["grasps"], out=tmp_path / "y",
                    repeats=2, noise=bad)


def test_protocol_runs_as_the_cli_runs_it(runs, binary, test_db_path, tmp_path):
    """protocol="shake" through the module equals `visgrab run --protocol shake` byte for byte
    and is recorded in run.csv; "lift" is the default run; an unknown name is a ValueError."""
    out = tmp_path / "module"
    trials = visgrab.run(visgrab.Database(test_db_path), runs["grasps"], threads=2, out=out,
                         protocol="shake")
    assert trials.results.sources["protocol"] == "shake"
    assert len(trials.results.sources["protocol_hash"]) == 16
    assert trials.results.sources["protocol_file"] == \
        os.path.normpath(os.path.join(visgrab.data_folder(), "protocols", "shake.xml"))
    cli(binary, "run", "--db", test_db_path, "--grasps", out / "grasp_list.csv", "--out",
        tmp_path / "cli", "--threads", "1", "--protocol", "shake", "--quiet")
    for name in ("trials.csv", "run.csv"):
        module_text = (out / name).read_text().replace(str(out / "grasp_list.csv"), "GRASPS")
        assert module_text == (tmp_path / "cli" / name).read_text().replace(
            str(out / "grasp_list.csv"), "GRASPS"), name
    lift = visgrab.run(visgrab.Database(test_db_path), runs["grasps"], threads=1,
                       out=tmp_path / "lift", protocol="lift")
    assert lift.results.sources["protocol"] == "lift"
    assert lift.results.sources["protocol_hash"] == ""
    assert lift.results.sources["protocol_file"] == ""
    assert (tmp_path / "lift" / "trials.csv").read_bytes() == \
        (runs["module"] / "trials.csv").read_bytes()
    with pytest.raises(ValueError, match='unknown protocol "wobble".*known: lift, shake'):
        visgrab.run(visgrab.Database(test_db_path), runs["grasps"], out=tmp_path / "w",
                    protocol="wobble")


def test_analyze_draws_a_shake_runs_pictures_with_the_shake(runs, test_db_path, tmp_path):
    """The report's pictures replay a run made with protocol="shake" with data_folder()'s
    protocols/shake.xml (found by run.csv's name and hash), as `visgrab analyze` does: drawn
    (a picture that cannot be drawn is left out), and not noted as differing from trials.csv."""
    out = tmp_path / "shake"
    visgrab.run(visgrab.Database(test_db_path), runs["grasps"], threads=2, out=out,
                protocol="shake")
    report = visgrab.analyze([out], out=tmp_path / "report", bootstrap=0)
    html = open(report, encoding="utf-8").read()
    images = sorted((tmp_path / "report" / "images").glob("*.png"))
    assert images
    for image in images:
        assert f'src="images/{image.name}"' in html, image.name
    assert "replayed as" not in html
