"""Shared fixtures of the Python module's tests: the shared 20-scene test database, the
`visgrab` program, and grasps for runs."""
import fcntl
import json
import os
import pathlib
import subprocess

import pytest

import visgrab

# The scenes of the shared test database (tests/support/test_database.hpp, kTestSceneIds) and its
# seed; the C++ suites make the same folder (same scenes, seed, data and camera), under the same
# lock, so whichever comes first generates it and the others reuse it.
TEST_SCENES = [
    "plain/single/cocacola/01", "plain/single/marmelade/03", "plain/single/saltbox/01",
    "plain/single/breadbox/05", "plain/single/corny/07", "plain/single/saltbox/06",
    "plain/double/breadbox_peachcan/03", "plain/double/cocacola_saltcylinder/01",
    "plain/double/burti_denkmit/05", "plain/double/cleaningbottle_sucker/06",
    "textured/single/cocacola/01", "textured/single/greencup/02", "textured/single/peachcan/02",
    "textured/single/tomato/04", "textured/single/sucker/08", "textured/single/saltbox/06",
    "textured/double/marmelade_pure/02", "textured/double/tomato_waterjug/04",
    "textured/double/burti_denkmit/05", "textured/double/cocacola_saltcylinder/06",
]
TEST_SEED = 3


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"${name} is not set (run the suites through ctest)")
    return value


@pytest.fixture(scope="session")
def test_db_path():
    """The shared test database, generated through the module when no suite made it yet."""
    path = pathlib.Path(_env("VISGRAB_TEST_DATABASE"))
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(f"{path}.lock", "a+") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            visgrab.generate_database(path, scenes=TEST_SCENES, threads=2, seed=TEST_SEED,
                                      camera="realistic")
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    return path


@pytest.fixture(scope="session")
def db(test_db_path):
    return visgrab.Database(str(test_db_path))


@pytest.fixture(scope="session")
def binary():
    return _env("VISGRAB_BINARY")


@pytest.fixture(scope="session")
def source_dir():
    return pathlib.Path(_env("VISGRAB_SOURCE_DIR"))


def cli(binary, *args, cwd=None, check=True):
    """Runs `visgrab ARGS`; returns the completed process."""
    result = subprocess.run([binary, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    if check and result.returncode != 0:
        raise AssertionError(f"visgrab {' '.join(map(str, args))}: exit {result.returncode}\n"
                             f"{result.stdout}\n{result.stderr}")
    return result


def cli_json(binary, *args):
    return json.loads(cli(binary, *args).stdout)


def trials_rows(path):
    """The rows of a trials.csv as dicts (a leading format comment line skipped)."""
    import csv
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))
