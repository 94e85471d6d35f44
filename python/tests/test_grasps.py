"""visgrab.Hand, Grasp, write_grasps and read_grasps: values against the hand files and the
grasp list reader's own messages (a file with the same bad value read by read_grasps, which is
what `visgrab run` reads)."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import visgrab

SCENE = "plain/single/cocacola/01"


def test_hand_by_name_folder_and_file(source_dir):
    sdh = visgrab.Hand("sdh")
    assert sdh.name == "SchunkHand" and sdh.dof == 7
    assert sdh.file == str(source_dir / "scenes/hands/sdh/sdh.grasp.xml")
    # The pre-shapes and their values are the description file's (read here with ElementTree).
    root = ET.parse(sdh.file).getroot()
    shapes = root.findall(".//PreShape")
    assert sdh.preshapes == [p.get("name") for p in shapes]
    for p in shapes:
        values = sdh.preshape(p.get("name"))
        np.testing.assert_allclose(values["q_open"], [float(v) for v in p.get("qOpen").split()])
        np.testing.assert_allclose(values["q_closed"],
                                   [float(v) for v in p.get("qClosed").split()])
        assert len(values["tau_max"]) == 7
    assert sdh.preshape("cyl")["name"] == "SDH_CYL"
    pg70 = visgrab.Hand(str(source_dir / "scenes/hands/pg70"))
    assert pg70.name == "PG70" and pg70.dof == 1
    assert visgrab.Hand(source_dir / "scenes/hands/pg70/pg70.grasp.xml").file == pg70.file
    assert "visgrab.Hand('SchunkHand', dof=7" in repr(sdh)


def test_hand_errors(tmp_path):
    with pytest.raises(ValueError, match=r'unknown hand "nohand".*known: .*pg70.*sdh'):
        visgrab.Hand("nohand")
    with pytest.raises(OSError, match="no such file or folder"):
        visgrab.Hand(str(tmp_path / "missing.grasp.xml"))
    bad = tmp_path / "bad.grasp.xml"
    bad.write_text("<GraspDescription>\n  <Oops/>\n")
    with pytest.raises(OSError, match=r"bad\.grasp\.xml:\d+"):
        visgrab.Hand(str(bad))
    with pytest.raises(ValueError, match=r'unknown pre-shape "SDH_NONE" for hand "SchunkHand"'):
        visgrab.Hand("sdh").preshape("SDH_NONE")


def test_grasp_kinds_and_attributes():
    g = visgrab.Grasp.preshape(scene=SCENE, method="mine", id="g1", preshape="SDH_CYL",
                               position=[0.01, -0.02, 0.15], quaternion=[0, 1, 0, 0])
    assert (g.scene, g.method, g.id, g.kind, g.preshape) == (SCENE, "mine", "g1", "preshape",
                                                             "SDH_CYL")
    np.testing.assert_array_equal(g.position, [0.01, -0.02, 0.15])
    np.testing.assert_allclose(g.quaternion, [0, 1, 0, 0], atol=1e-15)
    np.testing.assert_allclose(g.pose, [[1, 0, 0, 0.01], [0, -1, 0, -0.02], [0, 0, -1, 0.15],
                                        [0, 0, 0, 1]], atol=1e-15)
    assert g.q is None and g.contacts is None
    # The same grasp from its 4x4 pose; a repr that evaluates to an equal grasp.
    assert visgrab.Grasp.preshape(scene=SCENE, method="mine", id="g1", preshape="SDH_CYL",
                                  pose=g.pose) == g
    assert eval(repr(g), {"visgrab": visgrab}) == g
    # A non-normalised quaternion within 1e-3 is normalised, with w >= 0.
    turned = visgrab.Grasp.pose_q(scene=SCENE, method="mine", id="g2", q=np.zeros(7),
                                  position=(0, 0, 0.2), quaternion=[-0.7075, 0, 0, -0.7070])
    assert turned.kind == "pose_q" and list(turned.q) == [0.0] * 7
    assert turned.quaternion[0] > 0 and math.isclose(np.linalg.norm(turned.quaternion), 1.0)
    raw = visgrab.Grasp.raw(scene=SCENE, method="mine", id="g3", q_open=[0.1] * 7,
                            q_closed=[0.5] * 7, position=[0, 0, 0.3], quaternion=[1, 0, 0, 0])
    assert list(raw.q_open) == [0.1] * 7 and list(raw.q_closed) == [0.5] * 7
    assert raw.tau_max.size == 0
    limited = visgrab.Grasp.raw(scene=SCENE, method="mine", id="g5", q_open=np.zeros(7),
                                q_closed=np.ones(7), tau_max=np.full(7, 2.5), pose=np.eye(4))
    assert list(limited.tau_max) == [2.5] * 7
    with pytest.raises(ValueError, match="tau_max: expected shape"):
        visgrab.Grasp.raw(scene=SCENE, method="mine", id="g5", q_open=np.zeros(7),
                          q_closed=np.ones(7), tau_max=2.5, pose=np.eye(4))
    contacts = visgrab.Grasp.contacts(scene=SCENE, method="mine", id="g4",
                                      contacts=[[0.0, 0, 0.1, 1, 0, 0], [0.06, 0, 0.1, -1, 0, 0]])
    assert contacts.contacts.shape == (2, 6) and contacts.position is None
    np.testing.assert_array_equal(contacts.approach, [0, 0, -1])
    for grasp in (turned, raw, contacts):
        assert eval(repr(grasp), {"visgrab": visgrab}) == grasp


def reader_message(tmp_path, line):
    """What the grasp list reader (the CLI's) says about `line`: its message after 'error: '."""
    path = tmp_path / "one.csv"
    path.write_text(line + "\n")
    with pytest.raises(ValueError) as error:
        visgrab.read_grasps(path)
    text = str(error.value)
    assert text.startswith(f"{path}:1:"), text
    return text.split("error: ", 1)[1]


def test_bad_grasp_values_raise_the_readers_messages(tmp_path):
    cases = [
        (dict(position=[0, 0, math.nan], quaternion=[1, 0, 0, 0]),
         f"{SCENE}, m, g1, preshape, 0, 0, nan, 1, 0, 0, 0, SDH_CYL"),
        (dict(position=[0, 0, 0.1], quaternion=[1, 0, 0, 0.1]),
         f"{SCENE}, m, g1, preshape, 0, 0, 0.1, 1, 0, 0, 0.1, SDH_CYL"),
        (dict(position=[0, math.inf, 0.1], quaternion=[1, 0, 0, 0]),
         f"{SCENE}, m, g1, preshape, 0, inf, 0.1, 1, 0, 0, 0, SDH_CYL"),
    ]
    for kwargs, line in cases:
        with pytest.raises(ValueError) as error:
            visgrab.Grasp.preshape(scene=SCENE, method="m", id="g1", preshape="SDH_CYL", **kwargs)
        message = reader_message(tmp_path, line)
        assert str(error.value) == "Grasp.preshape(id='g1'): " + message
    with pytest.raises(ValueError, match="number of contacts: expected an integer from 2 to 3"):
        visgrab.Grasp.contacts(scene=SCENE, method="m", id="g", contacts=np.zeros((4, 6)))


def test_wrong_shapes_and_types_are_value_errors():
    base = dict(scene=SCENE, method="m", id="g", preshape="SDH_CYL")
    bad = [
        dict(position=[0, 0], quaternion=[1, 0, 0, 0]),
        dict(position=[[0, 0, 0]], quaternion=[1, 0, 0, 0]),
        dict(position=["a", "b", "c"], quaternion=[1, 0, 0, 0]),
        dict(position=[0, 0, 0], quaternion=[1, 0, 0, 0j]),
        dict(position=[0, 0, 0], quaternion=[True, False, False, False]),
        dict(position=[0, [0, 1], 0], quaternion=[1, 0, 0, 0]),
        dict(position=[0, 0, 0]),
        dict(pose=np.eye(3)),
        dict(pose=np.diag([1.0, 1.0, -1.0, 1.0])),
        dict(pose=np.eye(4), position=[0, 0, 0], quaternion=[1, 0, 0, 0]),
    ]
    for kwargs in bad:
        with pytest.raises(ValueError):
            visgrab.Grasp.preshape(**base, **kwargs)
    for name in ("scene", "method", "id"):
        for value in ("", "a,b", " a", "a#b", 3):
            with pytest.raises(ValueError, match=name):
                visgrab.Grasp.preshape(**{**base, name: value}, position=[0, 0, 0],
                                       quaternion=[1, 0, 0, 0])
    with pytest.raises(ValueError, match="q_closed: expected shape"):
        visgrab.Grasp.raw(scene=SCENE, method="m", id="g", q_open=[0] * 7, q_closed=np.zeros((7, 1)),
                          position=[0, 0, 0], quaternion=[1, 0, 0, 0])
    with pytest.raises(ValueError, match="q_closed must have as many values as q_open|q_closed"):
        visgrab.Grasp.raw(scene=SCENE, method="m", id="g", q_open=[0] * 7, q_closed=[0] * 6,
                          position=[0, 0, 0], quaternion=[1, 0, 0, 0])


def test_write_and_read_grasps(tmp_path):
    grasps = [
        visgrab.Grasp.preshape(scene=SCENE, method="mine", id=f"g{i}", preshape="SDH_BALL",
                               position=[0.001 * i, 0.1 / 3, 0.2], quaternion=[0, 0, 1, 0])
        for i in range(3)
    ] + [visgrab.Grasp.contacts(scene=SCENE, method="other", id="c1",
                                contacts=[[0.0, 0, 0.1, 1, 0, 0], [0.06, 0, 0.1, -1, 0, 0]],
                                approach=[0, 0, -2])]
    path = tmp_path / "mine.csv"
    visgrab.write_grasps(path, grasps)
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    assert len(lines) == 4 and lines[0].startswith(f"{SCENE},mine,g0,preshape,")
    back = visgrab.read_grasps(path)
    assert back == grasps
    # The numbers survive exactly (shortest round-trip text).
    assert back[1].position[1] == 0.1 / 3
    with pytest.raises(ValueError, match="expected visgrab.Grasp"):
        visgrab.write_grasps(path, ["not a grasp"])
    with pytest.raises(OSError):
        visgrab.write_grasps(tmp_path / "no" / "such" / "folder" / "g.csv", grasps)


def test_read_grasps_errors(tmp_path):
    with pytest.raises(OSError, match="missing.csv"):
        visgrab.read_grasps(tmp_path / "missing.csv")
    bad = tmp_path / "bad.csv"
    bad.write_text(f"# header\n{SCENE}, m, g1, preshape, 0, 0, 0.1, 1, 0, 0, 0, SDH_CYL\n"
                   f"{SCENE}, m, g2, preshape, 0, 0, 0.1, 1, 0, 0\n"
                   f"{SCENE}, m, g3, teleport, 0\n")
    with pytest.raises(ValueError) as error:
        visgrab.read_grasps(bad)
    lines = str(error.value).splitlines()
    assert len(lines) == 2
    assert lines[0].startswith(f"{bad}:3:") and lines[1].startswith(f"{bad}:4:")
    with pytest.warns(UserWarning, match=f"{bad}:3:"):
        good = visgrab.read_grasps(bad, strict=False)
    assert [g.id for g in good] == ["g1"]
    xml = tmp_path / "bad.xml"
    xml.write_text("<CartesianTask>\n<Oops>\n")
    with pytest.raises(OSError, match=r"bad\.xml:\d+"):
        visgrab.read_grasps(xml)
