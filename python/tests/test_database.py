"""visgrab.Database and Scene on the shared test database, against the files read here
independently (PNG, YAML, PLY decoded in this file) and `visgrab db list/show --json`."""
import re
import struct
import zlib

import numpy as np
import pytest

import visgrab
from conftest import TEST_SCENES, cli, cli_json

SCENE = "plain/single/cocacola/01"


def read_png(path):
    """A PNG file's pixels as numpy decodes them through Pillow (Debian python3-pil, which
    python3-matplotlib brings), else through the minimal reader below (slow: pure Python)."""
    try:
        from PIL import Image
    except ImportError:
        return read_png_minimal(path)
    with Image.open(path) as image:
        return np.array(image)


def read_png_minimal(path):
    """A non-interlaced 8/16-bit grey or RGB PNG as a numpy array (a minimal reader: zlib and
    the five row filters), independent of OpenCV."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert interlace == 0 and colour in (0, 2) and depth in (8, 16)
    channels = 3 if colour == 2 else 1
    bpp = channels * depth // 8
    stride = width * bpp
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(height, stride + 1)
    out = np.zeros((height, stride), np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        up = out[y - 1] if y > 0 else np.zeros(stride, np.int32)
        if kind == 0:
            out[y] = line
        elif kind == 2:
            out[y] = (line + up) & 255
        else:  # sub, average, Paeth: depend on the pixel to the left, byte by byte
            row = np.zeros(stride, np.int32)
            for x in range(stride):
                a = row[x - bpp] if x >= bpp else 0
                b = up[x]
                c = up[x - bpp] if x >= bpp else 0
                if kind == 1:
                    predictor = a
                elif kind == 3:
                    predictor = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                row[x] = (line[x] + predictor) & 255
            out[y] = row
    pixels = out.astype(np.uint8)
    if depth == 16:
        pixels = pixels.reshape(height, width * channels, 2)
        pixels = (pixels[..., 0].astype(np.uint16) << 8) | pixels[..., 1]
    return pixels.reshape(height, width, channels) if channels > 1 else pixels.reshape(height,
                                                                                        width)


def read_yaml_matrices(path):
    """The !!opencv-matrix nodes of an OpenCV YAML file: {name: array(rows, cols)}."""
    text = open(path).read()
    out = {}
    for m in re.finditer(r"^(\w+): !!opencv-matrix\s+rows: (\d+)\s+cols: (\d+)\s+dt: \w\s+"
                         r"data: \[([^\]]*)\]", text, re.M):
        values = [float(v) for v in m.group(4).replace("\n", " ").split(",")]
        out[m.group(1)] = np.array(values).reshape(int(m.group(2)), int(m.group(3)))
    return out


def read_ply(path):
    """The database's binary PLY: (header lines, structured array x y z red green blue)."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    count = int(next(line.split()[2] for line in header if line.startswith("element vertex")))
    dtype = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("red", "u1"), ("green", "u1"),
                      ("blue", "u1")])
    assert len(data) - end == count * dtype.itemsize
    return header, np.frombuffer(data[end:], dtype, count)


def test_scene_ids_are_the_cli_selection(db, binary, test_db_path):
    assert sorted(db.scene_ids()) == sorted(TEST_SCENES)
    assert len(db) == 20 and SCENE in db and "plain/single/cocacola/02" not in db
    for text in ("plain,single", "textured/double/*", "cocacola;pair=e", "!standing,single"):
        listed = cli_json(binary, "db", "list", "--db", test_db_path, "--scenes", text, "--json")
        ids = [s["id"] for s in listed["scenes"]]
        assert db.scene_ids(text) == ids, text
        assert ids, text
    # A list is the OR of its filters (a repeated --scenes).
    assert sorted(db.scene_ids(["plain/double/*", "textured/double/*"])) == \
        sorted(s for s in TEST_SCENES if "/double/" in s)
    assert db.source == "generated" and db.seed == 3


def test_images_are_the_png_files_in_rgb_order(db):
    s = db.scene(SCENE)
    files = s.files
    left, right = s.left, s.right
    assert left.shape == (540, 720, 3) and left.dtype == np.uint8
    np.testing.assert_array_equal(left, read_png(files["left_image"]))
    np.testing.assert_array_equal(right, read_png(files["right_image"]))
    np.testing.assert_array_equal(s.raw_left, read_png(files["raw_left_image"]))
    mask = s.mask
    assert mask.dtype == np.uint8
    np.testing.assert_array_equal(mask, read_png(files["mask"]))
    # The object's id and the table (255) are in the mask.
    assert set(np.unique(mask)) >= {s.ground_truth[0]["object"], 255}
    depth = s.depth
    assert depth.dtype == np.float32 and depth.shape == (540, 720)
    stored = read_png(files["depth"])
    np.testing.assert_allclose(depth, stored.astype(np.float64) / 10000.0, rtol=0, atol=1e-7)
    assert np.all(depth[stored == 0] == 0.0)
    disparity = s.disparity
    stored = read_png(files["disparity"])
    np.testing.assert_allclose(disparity[stored > 0], stored[stored > 0] / 256.0, rtol=1e-7)
    assert np.all(disparity[stored == 0] == -1.0)


def test_calibration_is_the_yaml_file(db):
    s = db.scene(SCENE)
    k = s.calibration
    yaml = read_yaml_matrices(s.files["calibration"])
    for name in ("K1", "K2", "R", "R1", "R2", "P1", "P2", "Q", "X_table_left"):
        np.testing.assert_array_equal(k[name], yaml[name], err_msg=name)
    for name in ("D1", "D2", "T"):
        np.testing.assert_array_equal(k[name], yaml[name].ravel(), err_msg=name)
    assert (k["width"], k["height"]) == (720, 540)
    np.testing.assert_allclose(k["X_table_camera"], yaml["X_table_left"] @ np.block(
        [[yaml["R1"].T, np.zeros((3, 1))], [np.zeros((1, 3)), np.ones((1, 1))]]), atol=1e-12)
    np.testing.assert_array_equal(s.cloud_frame, k["X_table_camera"])


def test_point_cloud_is_the_ply_file(db):
    s = db.scene(SCENE)
    header, vertices = read_ply(s.files["point_cloud"])
    cloud = s.point_cloud()
    assert cloud.shape == (len(vertices), 6) and cloud.dtype == np.float64
    assert len(vertices) > 1000
    for column, name in enumerate(("x", "y", "z", "red", "green", "blue")):
        np.testing.assert_array_equal(cloud[:, column], vertices[name].astype(np.float64))
    # The header's X_table_camera is cloud_frame (printed to 9 digits).
    line = next(h for h in header if "X_table_camera" in h)
    frame = np.array([float(v) for v in line.split(":")[-1].split()]).reshape(4, 4)
    np.testing.assert_allclose(s.cloud_frame, frame, atol=1e-8)
    table = s.point_cloud(frame="table")
    moved = (s.cloud_frame @ np.c_[cloud[:, :3], np.ones(len(cloud))].T).T[:, :3]
    np.testing.assert_allclose(table[:, :3], moved, atol=1e-12)
    np.testing.assert_array_equal(table[:, 3:], cloud[:, 3:])
    # In the table frame the points lie in the sampling box above the table.
    assert table[:, 2].min() > -0.021 and np.abs(table[:, :2]).max() <= 0.3 + 1e-6
    with pytest.raises(ValueError, match='frame must be "camera" or "table"'):
        s.point_cloud(frame="world")


def test_conditions_and_ground_truth_are_db_show(db, binary, test_db_path):
    for sid in (SCENE, "textured/double/marmelade_pure/02"):
        shown = cli_json(binary, "db", "show", "--db", test_db_path, sid, "--json")
        s = db.scene(sid)
        assert s.id == shown["id"] and s.original_id == shown["original_id"]
        c = s.conditions
        for key in ("texture", "kind", "arrangement", "pose", "description"):
            assert c[key] == shown["conditions"][key], key
        assert c["objects"] == [o["name"] for o in shown["conditions"]["objects"]]
        truth = s.ground_truth
        assert [t["object"] for t in truth] == [o["object"] for o in shown["ground_truth"]]
        for t, o in zip(truth, shown["ground_truth"]):
            np.testing.assert_allclose(t["pose"][:3, 3], o["position"], atol=1e-12)
        for name, entry in shown["files"].items():
            if entry is None:
                assert s.files[name] is None, name
            else:
                assert s.files[name] == entry["path"], name


def test_bad_input_raises_the_cli_errors(db, tmp_path, binary, test_db_path):
    with pytest.raises(ValueError, match=r'unknown scene.*plain/single/cocacola/01'):
        db.scene("plain/single/cocacola/1")
    with pytest.raises(ValueError) as error:
        db.scene_ids("plain,nosuchword")
    cli_error = cli(binary, "db", "list", "--db", test_db_path, "--scenes", "plain,nosuchword",
                    check=False).stderr
    assert str(error.value) in cli_error
    with pytest.raises(OSError, match="nothing: error: .*no such file"):
        visgrab.Database(str(tmp_path / "nothing"))
    # A corrupt copy of a scene's PLY: OSError naming the file.
    # (The index and that one file: the scene's other files are missing.)
    broken = tmp_path / "db"
    (broken / "scenes" / SCENE).mkdir(parents=True)
    (broken / "index.xml").write_bytes((test_db_path / "index.xml").read_bytes())
    cloud = broken / "scenes" / SCENE / "cloud.ply"
    cloud.write_bytes((test_db_path / "scenes" / SCENE / "cloud.ply").read_bytes()[:-7])
    copy = visgrab.Database(str(broken))
    with pytest.raises(OSError, match="cloud.ply"):
        copy.scene(SCENE).point_cloud()
    with pytest.raises(OSError, match="left.png"):
        copy.scene(SCENE).left
    assert "visgrab.Database(" in repr(db) and "20 scenes" in repr(db)
    assert repr(db.scene(SCENE)) == f"visgrab.Scene('{SCENE}')"


def test_the_minimal_png_reader_agrees_with_pillow(db):
    pytest.importorskip("PIL", reason="python3-pil is not installed: nothing to compare with")
    mask = db.scene(SCENE).files["mask"]
    np.testing.assert_array_equal(read_png_minimal(mask), read_png(mask))


def test_generate_database_gives_the_cli_files(tmp_path, binary):
    scene = "plain/single/saltbox/01"
    calls = []
    report = visgrab.generate_database(tmp_path / "py", scenes=f"id={scene}", threads=1, seed=7,
                                       progress=lambda *p: calls.append(p))
    assert report == {"generated": 1, "skipped": 0, "failures": []}
    assert calls[-1] == (1, 1, scene)
    cli(binary, "db", "generate", "--out", tmp_path / "cli", "--scenes", f"id={scene}",
        "--threads", "2", "--seed", "7", "--quiet")
    for name in ("left.png", "right.png", "calibration.yml", "cloud.ply", "depth.png"):
        assert (tmp_path / "py/scenes" / scene / name).read_bytes() == \
            (tmp_path / "cli/scenes" / scene / name).read_bytes(), name
    assert visgrab.Database(str(tmp_path / "py")).scene_ids() == [scene]
    # Again: the complete scene is skipped.
    assert visgrab.generate_database(tmp_path / "py", scenes=[f"id={scene}"], threads=1,
                                     seed=7)["skipped"] == 1
    with pytest.raises(ValueError, match="scenes: .*nosuchword"):
        visgrab.generate_database(tmp_path / "x", scenes="nosuchword")
    with pytest.raises(ValueError, match="selects no scene"):
        visgrab.generate_database(tmp_path / "x", scenes="id=nothing/*")
    with pytest.raises(ValueError, match="camera: "):
        visgrab.generate_database(tmp_path / "x", scenes=f"id={scene}", camera="nocamera")
    with pytest.raises(ValueError, match="threads"):
        visgrab.generate_database(tmp_path / "x", scenes=f"id={scene}", threads=0)
    with pytest.raises(ValueError, match="seed"):
        visgrab.generate_database(tmp_path / "x", scenes=f"id={scene}", seed=-1)
