"""VisGraB from Python: the scene database, hands, grasps, benchmark runs and the report.

The classes and functions call the project's C++ libraries (the same code as the `visgrab`
program), so a run from Python gives exactly the files `visgrab run` gives::

    import visgrab
    db = visgrab.Database("database")
    s = db.scene(db.scene_ids("plain/single/*")[0])
    g = visgrab.Grasp.preshape(scene=s.id, method="mine", id="g1",
                               position=[0.0, 0.0, 0.15], quaternion=[0, 1, 0, 0],
                               preshape="SDH_CYL")
    results = visgrab.run(db, [g], hand="sdh", threads=2)
    print(results[0].outcome, results[0].q_lift)

Errors: bad values (a grasp, a scene id, a pre-shape, an array of the wrong shape or type) raise
ValueError; files that are missing, unreadable or malformed raise OSError naming file:line. Long
calls (generate_database, run, analyze) release the GIL and use `threads` worker threads;
Ctrl-C stops them cleanly (the finished work stays on disk) and raises KeyboardInterrupt.
docs/python.md has the whole interface.
"""

import os
import pathlib
import shutil
import tempfile
import warnings

from . import _location
from ._visgrab import Database, Grasp, Hand, Results, Scene, TrialResult, __version__, engines
from . import _visgrab

__all__ = [
    "Database", "Scene", "Hand", "Grasp", "TrialResult", "Results", "RunTrials",
    "generate_database", "run", "write_grasps", "read_grasps", "read_results", "analyze",
    "data_folder", "engines", "__version__",
]


def data_folder():
    """The project's scene data folder (hands, objects, cameras, materials).

    As the `visgrab` program chooses it: $VISGRAB_DATA if set, else the installed
    PREFIX/share/visgrab/scenes next to this package, else the source tree's scenes/ (the
    package run from the build tree).
    """
    env = os.environ.get("VISGRAB_DATA")
    if env:
        return env
    if _location.PREFIX_FROM_PACKAGE is None:
        return _visgrab._source_scenes
    prefix = (pathlib.Path(__file__).resolve().parent / _location.PREFIX_FROM_PACKAGE).resolve()
    return str(_visgrab._default_data_folder(str(prefix)))


def _default_threads(threads):
    """threads, or the number of cores when None (the CLI's default)."""
    if threads is None:
        return max(1, os.cpu_count() or 1)
    if isinstance(threads, bool) or not isinstance(threads, int):
        raise ValueError(f"threads must be an integer >= 1, got {threads!r}")
    if threads < 1:
        raise ValueError(f"threads must be >= 1, got {threads}")
    return threads


# --- Hands ------------------------------------------------------------------------------------

def _as_hand(hand):
    if isinstance(hand, Hand):
        return hand
    return Hand("sdh" if hand is None else os.fspath(hand))


# --- Grasps -----------------------------------------------------------------------------------

def _numbers(name, value, shape):
    """value as a flat list of floats of the given shape (None in shape: any length).

    Raises ValueError for a wrong shape or a non-numeric type (numbers themselves, NaN included,
    are checked by the grasp list reader).
    """
    import numpy as np
    try:
        array = np.asarray(value)
    except Exception as e:  # ragged lists and the like
        raise ValueError(f"{name}: expected an array of numbers, got {value!r} ({e})") from None
    if array.dtype.kind not in "biuf":
        raise ValueError(f"{name}: expected numbers, got an array of dtype {array.dtype}")
    if array.dtype.kind == "b":
        raise ValueError(f"{name}: expected numbers, got booleans")
    if len(shape) != array.ndim or any(s is not None and s != a
                                       for s, a in zip(shape, array.shape)):
        want = "x".join("n" if s is None else str(s) for s in shape)
        raise ValueError(f"{name}: expected shape ({want}), got {array.shape}")
    return [float(v) for v in array.astype(np.float64).ravel()]


def _text(name, value):
    if not isinstance(value, str):
        raise ValueError(f"{name}: expected a string, got {value!r}")
    return value


def _pose_fields(position, quaternion, pose):
    """The seven pose numbers of a grasp list line from position + quaternion or a 4x4 pose."""
    import numpy as np
    if pose is not None:
        if position is not None or quaternion is not None:
            raise ValueError("give either pose or position and quaternion, not both")
        m = np.array(_numbers("pose", pose, (4, 4))).reshape(4, 4)
        if not np.all(np.isfinite(m)):
            raise ValueError(f"pose: expected finite numbers, got {m.tolist()}")
        r = m[:3, :3]
        if (not np.allclose(r @ r.T, np.eye(3), atol=1e-6) or np.linalg.det(r) < 0
                or not np.allclose(m[3], [0, 0, 0, 1])):
            raise ValueError("pose: expected a rigid transform (a rotation matrix and a last row "
                             f"0 0 0 1), got {m.tolist()}")
        return list(m[:3, 3]) + _quaternion_of(r)
    if position is None or quaternion is None:
        raise ValueError("a grasp needs position and quaternion (or pose)")
    return _numbers("position", position, (3,)) + _numbers("quaternion", quaternion, (4,))


def _quaternion_of(r):
    """The unit quaternion [w, x, y, z] of a rotation matrix (Shepperd's method)."""
    import numpy as np
    t = np.trace(r)
    if t > 0:
        s = 2.0 * np.sqrt(1.0 + t)
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
        q = [0.0, 0.0, 0.0, 0.0]
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    q = np.array(q) / np.linalg.norm(q)
    return [float(v) for v in q]


def _grasp(kind, scene, method, id, values):
    fields = [_text("scene", scene), _text("method", method), _text("id", id)]
    for name, field in zip(("scene", "method", "id"), fields):
        if any(c in field for c in ",#\r\n") or field != field.strip() or not field:
            raise ValueError(f"{name}: {field!r} must be non-empty, without commas, '#', line "
                             "breaks or surrounding blanks")
    text = ", ".join(fields + [kind] + [v if isinstance(v, str) else repr(v) for v in values])
    return Grasp._from_line(text, f"Grasp.{kind}(id={id!r})")


def _preshape(scene, method, id, preshape, position=None, quaternion=None, pose=None):
    """A grasp with a named pre-shape of the hand at a TCP pose.

    scene, method, id: strings (the grasp list's first fields); position (3,) in metres and
    quaternion [w, x, y, z] (unit within 1e-3), or pose (4x4); preshape: a name the hand
    defines (Hand.preshapes), checked when the grasp runs. Raises ValueError for bad values.
    """
    name = _text("preshape", preshape)
    if any(c in name for c in ",#\r\n") or name != name.strip() or not name:
        raise ValueError(f"preshape: {name!r} must be non-empty, without commas, '#', line "
                         "breaks or surrounding blanks")
    return _grasp("preshape", scene, method, id,
                  _pose_fields(position, quaternion, pose) + [name])


def _pose_q(scene, method, id, q, position=None, quaternion=None, pose=None):
    """A grasp given by a TCP pose and one hand configuration q (one value per DOF).

    q_closed and tau_max follow the hand's rule. Raises ValueError for bad values.
    """
    values = _numbers("q", q, (None,))
    return _grasp("pose_q", scene, method, id,
                  _pose_fields(position, quaternion, pose) + [len(values)] + values)


def _raw(scene, method, id, q_open, q_closed, tau_max=(), position=None, quaternion=None,
         pose=None):
    """A grasp in the simulator's own terms: TCP pose, q_open, q_closed (same length) and
    tau_max (empty: the hand's default rule). Raises ValueError for bad values.
    """
    q_open = _numbers("q_open", q_open, (None,))
    q_closed = _numbers("q_closed", q_closed, (None,))
    tau = _numbers("tau_max", tau_max, (None,))
    return _grasp("raw", scene, method, id,
                  _pose_fields(position, quaternion, pose) + [len(q_open)] + q_open
                  + [len(q_closed)] + q_closed + [len(tau)] + tau)


def _contacts(scene, method, id, contacts, approach=(0.0, 0.0, -1.0)):
    """A grasp given by 2 or 3 desired contacts and the approach direction.

    contacts: a (c, 6) array, each row a point (m) and a push direction (into the object);
    approach: the hand's direction of travel (default straight down). The benchmark solves
    the hand's configuration and placement. Raises ValueError for bad values.
    """
    rows = _numbers("contacts", contacts, (None, 6))
    return _grasp("contacts", scene, method, id,
                  [len(rows) // 6] + rows + _numbers("approach", approach, (3,)))


class _MakerOrAttribute:
    """Grasp.preshape(...) and Grasp.contacts(...) make grasps; g.preshape and g.contacts are
    a grasp's pre-shape name and contacts: a constructor on the class, the attribute on an
    instance."""

    def __init__(self, make, attribute):
        self.make = make
        self.attribute = attribute
        self.__doc__ = f"{make.__doc__}\n    On a grasp: {attribute.__doc__}"

    def __get__(self, grasp, cls=None):
        return self.make if grasp is None else self.attribute.__get__(grasp, cls)


Grasp.preshape = _MakerOrAttribute(_preshape, Grasp.__dict__["preshape"])
Grasp.contacts = _MakerOrAttribute(_contacts, Grasp.__dict__["contacts"])
Grasp.pose_q = staticmethod(_pose_q)
Grasp.raw = staticmethod(_raw)


def write_grasps(path, grasps):
    """Writes grasps as a grasp list file (docs/grasp-format.md), the input of `visgrab run`.

    Raises ValueError if something is not a Grasp, OSError if the file cannot be written.
    """
    grasps = list(grasps)
    for g in grasps:
        if not isinstance(g, Grasp):
            raise ValueError(f"write_grasps: expected visgrab.Grasp objects, got {g!r}")
    _visgrab._write_grasps(os.fspath(path), grasps)


def read_grasps(path, strict=True):
    """The grasps of a grasp file (any format `visgrab run` reads) or a folder of them.

    strict=True raises ValueError listing every rejected grasp (file:line:column: error: ...);
    strict=False returns the good grasps and warns about the others. OSError for a file that
    cannot be read or a malformed XML file.
    """
    grasps, rejected, notes = _visgrab._read_grasps(os.fspath(path))
    if rejected and strict:
        raise ValueError("\n".join(rejected))
    for message in (rejected if not strict else []) + notes:
        warnings.warn(message, stacklevel=2)
    return grasps


# --- Database ---------------------------------------------------------------------------------

def generate_database(out, scenes=None, threads=None, camera="realistic", seed=1, data=None,
                      objects=None, progress=None):
    """Generates a scene database into `out`, as `visgrab db generate` does.

    scenes: a filter (the CLI's --scenes syntax, or a list of filters OR-ed; None: all 432);
    threads: worker threads (None: the number of cores); camera: a profile name of
    DATA/cameras or a profile file; seed: placements and sensor noise (the same seed gives the
    same files whatever the thread count); data: the scene data folder (default data_folder());
    objects: your own object spec (`db generate --objects`); progress: called as
    progress(done, total, last_id) from the calling thread.
    An existing generation with the same seed is continued. Returns a dict (generated, skipped,
    failures); raises RuntimeError when scenes failed, ValueError for a bad filter or camera,
    OSError for unreadable inputs, KeyboardInterrupt on Ctrl-C (finished scenes are kept).
    """
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    report = _visgrab._generate_database(
        os.fspath(out), scenes, _default_threads(threads), os.fspath(camera), seed,
        os.fspath(data) if data is not None else data_folder(),
        os.fspath(objects) if objects is not None else None, progress)
    if report["failures"]:
        raise RuntimeError(f"{len(report['failures'])} scene(s) could not be generated:\n"
                           + "\n".join(report["failures"]))
    return report


# --- Runs -------------------------------------------------------------------------------------

class RunTrials(list):
    """The trials of a run (a list of TrialResult in canonical order: scene, method, rank).

    Also: summary (dict: trials, resumed, rejected, outcomes, scenes, methods, as `visgrab run`
    prints it), rejected (the rejected grasps' messages) and results (the Results object).
    """

    def __init__(self, results, summary):
        super().__init__(results.trials)
        self.results = results
        self.summary = summary
        self.rejected = summary["rejected"]


def run(db, grasps, hand=None, threads=None, out=None, scenes=None, resume=False, strict=True,
        progress=None, engine="ode", repeats=1, noise=None, seed=1, adaptive=False,
        protocol=None):
    """Runs grasps through the simulator, as `visgrab run` does; returns a RunTrials list.

    db: a Database or its path; grasps: Grasp objects; hand: a Hand, a hand name or path
    (default "sdh"); threads: worker threads (None: the number of cores; the results do not
    depend on it); out: the result folder to write (trials.csv, run.csv and the grasp list
    grasp_list.csv the run read, so `visgrab render --results` and `visgrab analyze` work on it);
    None: a temporary folder, removed afterwards; scenes: only the scenes this filter selects;
    resume: continue an interrupted run in `out`; progress: called as progress(done, total)
    from the calling thread; engine: the physics engine, "ode" (the benchmark's, default) or
    "mujoco" (when this build has it: visgrab.engines()), recorded in run.csv; an engine the
    build lacks is a ValueError that says how to get it; protocol: the trial protocol, "lift"
    (the paper's, also None), "shake" (ACRONYM's) or a protocol file (docs/protocols.md), as
    `visgrab run --protocol`; an unknown name is a ValueError, a bad file an OSError naming its
    line.

    Robust verdicts, as `visgrab run --repeats N --noise FILE --seed S --adaptive`: repeats=N
    runs each grasp N times, repeat 0 unperturbed and repeats 1..N-1 under seeded perturbations
    of the noise model (noise: an XML file, None: the documented defaults; docs/noise-model.md);
    each TrialResult then has its .repeat and .seed, and `out` holds grasps.csv with every
    grasp's P(success) and Wilson interval. adaptive=True stops repeating a grasp once its first
    trials agree. repeats=1 (default) is the plain run; noise or adaptive without repeats > 1 is
    a ValueError, a bad noise file an OSError naming its file and line.

    The grasps are written with the grasp list writer and the runner reads that file, exactly
    as `visgrab run --grasps FILE` would: trials.csv is byte-identical. strict=True (default)
    raises ValueError before running if any grasp would be rejected (unknown scene, unknown
    pre-shape, wrong number of joint values, duplicate id; message as the CLI's, naming the
    line of grasp_list.csv); strict=False runs the others and lists the rejected in .rejected.
    OSError: unreadable database, scene files or hand; an existing trials.csv in `out` without
    resume is a RuntimeError. Ctrl-C stops the run (finished trials are written; resume=True
    continues) and raises KeyboardInterrupt.
    """
    if not isinstance(db, Database):
        db = Database(os.fspath(db))
    for name, value in (("repeats", repeats), ("seed", seed)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"{name} must be an int, not {type(value).__name__}")
    hand = _as_hand(hand)
    threads = _default_threads(threads)
    grasps = list(grasps)
    if scenes is not None and not isinstance(scenes, str):
        scenes = ";".join(scenes)
    with tempfile.TemporaryDirectory(prefix="visgrab-run-") as tmp:
        folder = pathlib.Path(tmp if out is None else os.fspath(out))
        if not resume and (folder / "trials.csv").exists():
            # Checked before grasp_list.csv is written: the earlier run's input stays as it was.
            raise RuntimeError(f"{folder / 'trials.csv'} already holds results; resume them "
                               "(resume=True) or choose another folder")
        folder.mkdir(parents=True, exist_ok=True)
        grasp_file = folder / "grasp_list.csv"
        write_grasps(grasp_file, grasps)
        if strict:
            problems = _visgrab._grasp_problems(db, hand, str(grasp_file))
            if problems:
                raise ValueError("\n".join(problems))
        summary = _visgrab._run(db.path, str(grasp_file), str(folder), hand.file, scenes or "",
                                threads, resume, engine, progress, int(repeats),
                                "" if noise is None else os.fspath(noise), int(seed),
                                bool(adaptive), _protocol_file(protocol))
        return RunTrials(read_results(folder), summary)


def _protocol_file(protocol):
    """The protocol file `protocol` names (cli::protocolPath's rules); "" for None."""
    if protocol is None:
        return ""
    text = os.fspath(protocol)
    if "/" in text or text.endswith(".xml") or os.path.isfile(text):
        return text
    folder = pathlib.Path(data_folder()) / "protocols"
    if (folder / (text + ".xml")).is_file():
        return str(folder / (text + ".xml"))
    known = ", ".join(sorted(p.stem for p in folder.glob("*.xml")))
    raise ValueError(f'unknown protocol "{text}": not a file, and {folder} has no protocol of '
                     f"that name (known: {known})")


def read_results(dir):
    """Reads a result folder of `visgrab run` (trials.csv, run.csv) with the C++ reader.

    Returns a Results object: trials (list[TrialResult], canonical order), scenes, methods,
    rejected, sources, label, finished; iterating it goes over the trials. A torn last line (a
    killed run) is dropped with a warning; a run that has not finished (unfinished.txt) is read
    with a warning and finished=False. OSError (file:line) for a missing or corrupt file.
    """
    results, notes = _visgrab._read_results(os.fspath(dir))
    for message in notes:
        warnings.warn(message, stacklevel=2)
    return results


def analyze(dirs, out, threads=None, pictures=True, ci_level=0.95, bootstrap=2000, seed=None,
            allow_unfinished=False):
    """Writes the report of one or more result folders, as `visgrab analyze DIRS --out OUT`.

    The paper's analyses: CSV tables, report.md, report.html with SVG plots and (pictures=True,
    the CLI's default; False = --no-pictures) pictures of the best, a typical and a failed
    grasp per method and condition (a run made with another protocol than the lift is drawn
    with data_folder()'s protocols/NAME.xml when it has the recorded hash, as the CLI's
    --data; docs/protocols.md). Every estimate gets a `ci_level` interval from a scene
    bootstrap of `bootstrap` resamples (--ci-level, --bootstrap; 0 = no intervals, no overall
    success rates and no comparisons; else at least 100), seeded with `seed` (--seed; None =
    the CLI's default): the same seed gives the same intervals with any `threads`. Folders of
    the same name are labelled by the shortest trailing paths that differ (benchA/results,
    benchB/results), as the CLI labels them. A run that has not finished (its folder holds
    unfinished.txt: stopped, killed or failed, or still running) is refused with ValueError
    unless allow_unfinished=True (--allow-unfinished), which analyses the trials it has and
    says so in the report. Returns the path of report.html. OSError for unreadable result
    folders, ValueError for options out of range (named as here) and for one folder given twice.
    """
    if isinstance(dirs, (str, os.PathLike)):
        dirs = [dirs]
    if isinstance(bootstrap, bool) or not isinstance(bootstrap, int):
        raise ValueError(f"bootstrap must be an integer (0 or at least 100), got {bootstrap!r}")
    if isinstance(ci_level, bool) or not isinstance(ci_level, (int, float)):
        raise ValueError(f"ci_level must be a number between 0 and 1, got {ci_level!r}")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    notes = _visgrab._analyze([os.fspath(d) for d in dirs], os.fspath(out),
                              _default_threads(threads), bool(pictures), float(ci_level),
                              bootstrap, seed, bool(allow_unfinished))
    for message in notes:
        warnings.warn(message, stacklevel=2)
    return os.path.join(os.fspath(out), "report.html")


# --- Imported grasps (docs/grasp-format.md, "Importing grasps") -------------------------------

def _jaw(scene, method, id, width, position=None, quaternion=None, pose=None, score=None):
    """A parallel-jaw grasp: the jaw frame's pose in the table frame (origin between the finger
    pads, z the approach, x the closing axis) and the opening it needs (width, m), with the
    method's score if any. Any hand that declares a jaw frame runs it (e.g. "franka").
    Raises ValueError for bad values.
    """
    values = _pose_fields(position, quaternion, pose) + _numbers("width", width, ())
    if score is not None:
        values += _numbers("score", score, ())
    return _grasp("jaw", scene, method, id, values)


Grasp.jaw = staticmethod(_jaw)


def _contact_graspnet_arrays(file, allow_pickle):
    """(grasps, scores, widths or None) of a Contact-GraspNet .npz: the plain arrays, or the
    inference script's pickled dicts (pred_grasps_cam, scores per segment) when allow_pickle."""
    import numpy as np
    with np.load(file, allow_pickle=False) as data:
        names = set(data.files)
    if "pred_grasps_cam" not in names or "grasps" in names:
        return None
    if not allow_pickle:
        raise ValueError(f"{file}: Contact-GraspNet's pickled output (pred_grasps_cam): "
                         "unpickling runs code from the file, so it is refused by default; "
                         "import_grasps(..., allow_pickle=True) reads it (trusted files only)")
    with np.load(file, allow_pickle=True) as data:
        grasps = data["pred_grasps_cam"].item()
        scores = data["scores"].item()
    keys = sorted(grasps)
    if not keys:
        return np.zeros((0, 4, 4)), np.zeros((0,)), None
    return (np.concatenate([np.asarray(grasps[k], dtype=np.float64).reshape(-1, 4, 4)
                            for k in keys]),
            np.concatenate([np.asarray(scores[k], dtype=np.float64).reshape(-1) for k in keys]),
            None)


def import_grasps(format, file, db, scene=None, hand="franka", method=None, strict=False,
                  allow_pickle=False):
    """The grasps of a method's file as jaw grasps, as `visgrab import` reads them.

    format: "graspnet" (graspnetAPI's GraspGroup .npy), "contact-graspnet" (a .npz) or
    "acronym" (ACRONYM's .h5 or GraspGen's .json); db: a Database or its path; scene: the scene
    id (required for the camera-frame formats; acronym: default the scene made from the file);
    hand: a Hand, name or path whose jaw frame places the grasps; method: their method name
    (default the format's name). Each grasp's id is its index in the file and its score is kept.

    Contact-GraspNet's inference script saves pickled dicts (pred_grasps_cam, scores per
    segment): with allow_pickle=True they are read with numpy.load(allow_pickle=True) and
    concatenated in segment order. Unpickling runs code from the file: pass it for trusted files
    only. The default, allow_pickle=False (numpy's own), refuses them with a ValueError saying
    so; the CLI never unpickles.

    Rejected grasps (a width the hand cannot open, a non-orthonormal rotation, NaN, ...) are
    warnings ("file: grasp INDEX: why"), or a ValueError listing them with strict=True. OSError:
    a file that cannot be read (missing key, wrong shape); ValueError: unknown format or scene.
    """
    if not isinstance(db, Database):
        db = Database(os.fspath(db))
    hand = hand if isinstance(hand, Hand) else Hand("franka" if hand is None else os.fspath(hand))
    file = os.fspath(file)
    method = "" if method is None else _text("method", method)
    arrays = None
    import zipfile
    if format == "contact-graspnet" and zipfile.is_zipfile(file):
        arrays = _contact_graspnet_arrays(file, allow_pickle)  # else the C++ reader says why
    if arrays is not None:
        grasps, rejected = _visgrab._import_contact_graspnet_arrays(
            arrays[0], arrays[1], arrays[2], file, db, scene, hand, method)
    else:
        grasps, rejected = _visgrab._import_grasps(format, file, db, scene, hand, method)
    if rejected and strict:
        raise ValueError("\n".join(rejected))
    for message in rejected:
        warnings.warn(message, stacklevel=2)
    return grasps


__all__ += ["import_grasps"]
