#!/usr/bin/env python3
"""Tests of scripts/check-includes.py on a small fake tree and module map (CTest:
include_graph_checker). A violation must fail with its file:line message; linked includes,
directly or through PUBLIC links, must pass."""

import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "check-includes.py")


def target(root, name, folder, sources, public=(), private=()):
    """One map entry as cmake/VisgrabModuleMap.cmake writes it for a static library."""
    return {
        "name": name,
        "type": "STATIC_LIBRARY",
        "source_dir": os.path.join(root, "src", folder),
        "SOURCES": list(sources),
        "INCLUDE_DIRECTORIES": [os.path.join(root, "src")],
        "INTERFACE_INCLUDE_DIRECTORIES": [os.path.join(root, "src")],
        "LINK_LIBRARIES": list(public) + list(private) + ["Some::External"],
        "INTERFACE_LINK_LIBRARIES": list(public) + [f"$<LINK_ONLY:{p}>" for p in private],
    }


class CheckIncludesTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        files = {
            "src/a/a.hpp": "#pragma once\n",
            "src/a/a.cpp": '#include "a/a.hpp"\n',
            "src/b/b.hpp": '#pragma once\n#include "a/a.hpp"\n',
            "src/b/b.cpp": '#include "b/b.hpp"\n#include <vector>\n#include "generated.hpp"\n',
            "src/c/c.cpp": '// uses both\n#include "b/b.hpp"\n#include "a/a.hpp"\n',
        }
        for path, text in files.items():
            full = os.path.join(self.root, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w", encoding="utf-8") as f:
                f.write(text)

    def tearDown(self):
        self.tmp.cleanup()

    def run_checker(self, targets, extra=()):
        path = os.path.join(self.root, "module_map.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump({"source_dir": self.root, "targets": targets}, f)
        done = subprocess.run([sys.executable, SCRIPT, path, *extra], capture_output=True,
                              text=True, check=False)
        return done.returncode, done.stdout + done.stderr

    def test_public_links_pass_on(self):
        rc, out = self.run_checker([
            target(self.root, "a", "a", ["a.cpp"]),
            target(self.root, "b", "b", ["b.cpp"], public=["a"]),
            target(self.root, "c", "c", ["c.cpp"], private=["b"]),
        ])
        self.assertEqual(rc, 0, out)

    def test_private_links_do_not_pass_on(self):
        rc, out = self.run_checker([
            target(self.root, "a", "a", ["a.cpp"]),
            target(self.root, "b", "b", ["b.cpp"], private=["a"]),
            target(self.root, "c", "c", ["c.cpp"], private=["b"]),
        ])
        self.assertEqual(rc, 1, out)
        self.assertEqual(
            out.splitlines()[0],
            "src/c/c.cpp:3: includes a/a.hpp of target a, which c does not link")
        self.assertEqual(len(out.splitlines()), 2, out)  # the violation and the summary

    def test_missing_link_fails_in_headers_too(self):
        rc, out = self.run_checker([
            target(self.root, "a", "a", ["a.cpp"]),
            target(self.root, "b", "b", ["b.cpp"]),
            target(self.root, "c", "c", ["c.cpp"], private=["a", "b"]),
        ])
        self.assertEqual(rc, 1, out)
        self.assertIn("src/b/b.hpp:2: includes a/a.hpp of target a, which b does not link", out)
        self.assertNotIn("src/c/", out)

    def linked_chain(self):
        """c links b privately, b links a privately: c's includes are fine (it includes b only
        through b.hpp, which includes a.hpp: b's own business), but c links a."""
        return [
            target(self.root, "a", "a", ["a.cpp"]),
            target(self.root, "b", "b", ["b.cpp"], public=["a"]),
            target(self.root, "c", "c", ["c.cpp"], private=["b"]),
        ]

    def test_a_forbidden_link_through_a_chain_fails_with_the_chain(self):
        rc, out = self.run_checker(self.linked_chain(), ["--not-linking", "c,b=a,Some::Engine"])
        self.assertEqual(rc, 1, out)
        self.assertIn("c links a (c -> b -> a), which it must not", out)
        self.assertIn("b links a (b -> a), which it must not", out)

    def test_an_external_forbidden_link_is_found_too(self):
        rc, out = self.run_checker(self.linked_chain(), ["--not-linking", "c=Some::External"])
        self.assertEqual(rc, 1, out)
        self.assertIn("c links Some::External (c -> Some::External), which it must not", out)

    def test_targets_free_of_the_forbidden_ones_pass(self):
        rc, out = self.run_checker(self.linked_chain(), ["--not-linking", "a=b,c"])
        self.assertEqual(rc, 0, out)
        self.assertIn("a link none of the targets they must not", out)

    def test_a_malformed_rule_or_unknown_target_is_an_error(self):
        rc, out = self.run_checker(self.linked_chain(), ["--not-linking", "c-a"])
        self.assertEqual(rc, 2, out)
        rc, out = self.run_checker(self.linked_chain(), ["--not-linking", "nosuch=a"])
        self.assertEqual(rc, 2, out)
        self.assertIn("nosuch", out)

    def test_bad_map_is_an_error_not_a_pass(self):
        path = os.path.join(self.root, "module_map.json")
        with open(path, "w", encoding="utf-8") as f:
            f.write("{not json")
        done = subprocess.run([sys.executable, SCRIPT, path], capture_output=True, text=True,
                              check=False)
        self.assertEqual(done.returncode, 2)


if __name__ == "__main__":
    unittest.main()
