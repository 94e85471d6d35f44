#!/usr/bin/python3
"""`visgrab wc info | db list | db show | grasp --json`: the output parses and matches its schema
(docs/schemas), and says what the input holds.

Usage: json_schema_test.py VISGRAB_BINARY SOURCE_DIR
Needs Debian's python3-jsonschema (scripts/bootstrap.sh installs it). Exit 0 when every check
passes, 1 with the failures listed otherwise.
"""
import json
import math
import pathlib
import subprocess
import sys
import tempfile

import jsonschema

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def load_schemas(folder):
    """Every schema of docs/schemas by its $id, checked against its meta-schema."""
    store = {}
    for path in sorted(folder.glob("*.schema.json")):
        schema = json.loads(path.read_text())
        jsonschema.Draft202012Validator.check_schema(schema)
        store[schema["$id"]] = schema
    return store


def validate(store, name, document, what):
    schema = store["urn:visgrab:schema:" + name]
    resolver = jsonschema.RefResolver.from_schema(schema, store=store)
    validator = jsonschema.Draft202012Validator(schema, resolver=resolver)
    errors = sorted(validator.iter_errors(document), key=lambda e: list(e.path))
    for e in errors:
        failures.append(f"{what}: {'/'.join(map(str, e.path))}: {e.message}")


def run_json(binary, args, what):
    """Runs visgrab with args; the parsed JSON of its stdout (None after a failure)."""
    r = subprocess.run([binary] + args, capture_output=True, text=True)
    if r.returncode != 0:
        failures.append(f"{what}: exit {r.returncode}: {r.stderr}")
        return None
    try:
        # Strict JSON: NaN and Infinity are not JSON and must not appear.
        return json.loads(r.stdout, parse_constant=lambda c: failures.append(f"{what}: {c}"))
    except json.JSONDecodeError as e:
        failures.append(f"{what}: not JSON: {e}\n{r.stdout[:500]}")
        return None


def check_wc_info(binary, source, store, tmp):
    sdh = run_json(binary, ["wc", "info", "--json", str(source / "scenes/hands/sdh/sdh.wc.xml")],
                   "wc info sdh")
    if sdh is not None:
        validate(store, "wc-info", sdh, "wc info sdh")
        devices = {d["name"]: d for d in sdh["devices"]}
        check(devices.get("SchunkHand", {}).get("dof") == 7, "wc info sdh: SchunkHand has 7 DOF")
        joints = devices.get("SchunkHand", {}).get("joints", [])
        active = [j["q_index"] for j in joints if j["q_index"] is not None]
        check(active == list(range(7)), f"wc info sdh: q indices {active}")
        names = [f["name"] for f in sdh["frames"]]
        check(names[0] == "WORLD" and sdh["frames"][0]["parent"] is None, "wc info: WORLD first")
        for f in sdh["frames"][1:]:
            check(f["parent"] in names[: names.index(f["name"])],
                  f"wc info: {f['name']}'s parent comes before it")
    # A name that needs escaping and a joint without limits (infinite: null).
    wc = tmp / "escape.wc.xml"
    wc.write_text('<WorkCell name="quote&quot; backslash\\ tab&#9;end">\n'
                  '  <SerialDevice name="Arm">\n'
                  '    <Frame name="Base"/>\n'
                  '    <Joint name="J" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0.1</Pos></Joint>\n'
                  '  </SerialDevice>\n'
                  '</WorkCell>\n')
    doc = run_json(binary, ["wc", "info", str(wc), "--json"], "wc info escape")
    if doc is not None:
        validate(store, "wc-info", doc, "wc info escape")
        check(doc["name"] == 'quote" backslash\\ tab\tend', f"wc info: name {doc['name']!r}")
        joint = doc["devices"][0]["joints"][0]
        check(joint["limits"]["upper"] is None and joint["limits"]["lower"] is None,
              f"wc info: unlimited joint limits are null: {joint['limits']}")
        check(abs(doc["frames"][-1]["position"][2] - 0.1) < 1e-12, "wc info: joint position")

    # A parallel device (a four-bar linkage): its junction, legs and joint classes.
    wc = tmp / "fourbar.wc.xml"
    wc.write_text('<WorkCell name="FourBar">\n <ParallelDevice name="F">\n'
                  '  <Frame name="Base"/>\n'
                  '  <SerialChain name="Crank">\n'
                  '   <Joint name="A" type="Revolute"/>\n'
                  '   <Joint name="B" type="Revolute" state="Passive"><RPY>0 0 0</RPY>'
                  '<Pos>2 0 0</Pos></Joint>\n'
                  '   <Frame name="End"><RPY>0 0 0</RPY><Pos>2.5 0 0</Pos></Frame>\n'
                  '  </SerialChain>\n'
                  '  <Frame name="Ground" refframe="Base"><RPY>0 0 0</RPY><Pos>3 0 0</Pos></Frame>\n'
                  '  <SerialChain name="Rocker">\n'
                  '   <Joint name="C" type="Revolute" state="Passive"/>\n'
                  '   <Joint name="D" type="Revolute" state="Passive"><RPY>0 0 0</RPY>'
                  '<Pos>2 0 0</Pos></Joint>\n'
                  '  </SerialChain>\n'
                  '  <Junction><Chains>Crank</Chains><Chains>Rocker</Chains></Junction>\n'
                  ' </ParallelDevice>\n</WorkCell>\n')
    doc = run_json(binary, ["wc", "info", str(wc), "--json"], "wc info parallel")
    if doc is not None:
        validate(store, "wc-info", doc, "wc info parallel")
        device = doc["devices"][0]
        check(device["kind"] == "parallel" and device["dof"] == 1,
              f"wc info parallel: kind {device['kind']}, dof {device['dof']}")
        p = device.get("parallel", {})
        check(p.get("full_dof") == 4, f"wc info parallel: full DOF {p.get('full_dof')}")
        check(p.get("passive_joints") == ["F.Crank.B", "F.Rocker.C", "F.Rocker.D"],
              f"wc info parallel: passive joints {p.get('passive_joints')}")
        legs = p.get("junctions", [{}])[0].get("legs", [])
        check([(l["chains"], l["start"], l["end"]) for l in legs] ==
              [(["Crank"], "F.Base", "F.Crank.End"), (["Rocker"], "F.Base", "F.Rocker.D")],
              f"wc info parallel: legs {legs}")


def check_database(binary, store, tmp):
    db = tmp / "db"
    scene = "plain/single/cocacola/01"
    r = subprocess.run([binary, "db", "generate", "--out", str(db), "--scenes",
                        "plain,single,cocacola,pose=1", "--threads", "1", "--quiet"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        failures.append(f"db generate: exit {r.returncode}: {r.stderr}")
        return
    listing = run_json(binary, ["db", "list", "--db", str(db), "--json"], "db list")
    if listing is not None:
        validate(store, "db-list", listing, "db list")
        check([s["id"] for s in listing["scenes"]] == [scene], f"db list: {listing['scenes']}")
        check(listing["total"] == 1, "db list: total 1")
        c = listing["scenes"][0]["conditions"] if listing["scenes"] else None
        check(c is not None and c["objects"] == [{"id": 5, "name": "cocacola"}] and
              c["pose"] == 1 and c["arrangement"] == "standing", f"db list: conditions {c}")
    none = run_json(binary, ["db", "list", "--db", str(db), "--json", "--scenes", "textured"],
                    "db list textured")
    if none is not None:
        validate(store, "db-list", none, "db list textured")
        check(none["scenes"] == [] and none["total"] == 1, "db list: the filter selects none")
    show = run_json(binary, ["db", "show", "--json", "--db", str(db), scene], "db show")
    if show is not None:
        validate(store, "db-show", show, "db show")
        check(show["id"] == scene, "db show: id")
        check(show["files"]["left_image"]["exists"], "db show: the left image exists")
        for name in ["disparity", "point_cloud", "depth", "mask", "poses"]:
            check(show["files"][name] is not None and show["files"][name]["exists"],
                  f"db show: the generated scene's {name} exists")
        for name in ["raw_left_image", "raw_right_image"]:
            check(show["files"][name] is not None and show["files"][name]["exists"],
                  f"db show: the realistic camera's {name} exists")
        check(show["files"]["collision_mesh"] is None, "db show: a generated scene has no mesh")
        truth = show["ground_truth"]
        check(len(truth) == 1 and truth[0]["name"] == "cocacola", f"db show: ground truth {truth}")
        if truth:
            q = truth[0]["quaternion"]
            check(abs(math.sqrt(sum(v * v for v in q)) - 1) < 1e-9, "db show: unit quaternion")
    return db


def check_grasp(binary, source, store):
    scene = source / "tests/rwsim/simulator/data/sdh_box.dwc.xml"
    doc = run_json(binary, ["grasp", str(scene), "--hand", "SchunkHand", "--pose", "0", "0", "0.05",
                            "0", "180", "0", "--qopen=-1.048,0.174,0,-1.048,0.174,-1.048,0.174",
                            "--qclose", "0", "0.349", "0", "0", "0.349", "0", "0.349",
                            "--taumax", "2.1,1.4,2.1,1.05,0.7,1.05,0.7", "--json"], "grasp")
    if doc is not None:
        validate(store, "grasp", doc, "grasp")
        # The simulator tests' cylinder grasp holds the box (sim_cli_test: stable, code 1).
        check(doc["outcome"] == "stable" and doc["robwork_code"] == 1, f"grasp: {doc['outcome']}")
        check(doc["hand"] == "SchunkHand" and len(doc["q_grasp"]) == 7, "grasp: hand and q")
        check(doc["object"] == "Box" and len(doc["contacts"]) > 0, "grasp: contacts on the box")


def main():
    binary, source = sys.argv[1], pathlib.Path(sys.argv[2])
    store = load_schemas(source / "docs/schemas")
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        check_wc_info(binary, source, store, tmp)
        check_database(binary, store, tmp)
        check_grasp(binary, source, store)
    for f in failures:
        print("FAILED:", f)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
