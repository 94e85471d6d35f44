#!/usr/bin/env python3
"""Tests of scripts/compare-trials.py (CTest: compare_trials_script) on small trials.csv files
whose differences are counted by hand."""

import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "compare-trials.py")
HEADER = ("scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,"
          "simulated_time,detail\n")


def row(scene, grasp, outcome, time):
    return f"{scene},m,{grasp},0,{outcome},1,0,0,0,1,{time},\"x, y\"\n"


class CompareTrials(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def write(self, name, text):
        path = os.path.join(self.dir.name, name)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        return path

    def run_script(self, *args):
        return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                              check=False)

    def test_counts_the_verdicts_that_differ(self):
        a = self.write("a.csv", "# visgrab trials 2\n" + HEADER + row("s1", "g1", "stable", 1.5) +
                       row("s1", "g2", "slipped", 1.25) + row("s2", "g1", "stable", 1.0) +
                       row("s2", "g2", "in_collision", 0) + row("s3", "g1", "missed", 0.5))
        # s1/g1 stable -> slipped, s2/g1 stable -> slipped, s1/g2 slipped -> dropped; s3 only in A,
        # s4 only in B.
        b = self.write("b.csv", HEADER + row("s2", "g2", "in_collision", 0) +
                       row("s1", "g1", "slipped", 1.5) + row("s1", "g2", "dropped", 1.0) +
                       row("s2", "g1", "slipped", 1.0) + row("s4", "g1", "stable", 2.0))
        out = self.run_script(a, b, "--list", "1")
        self.assertEqual(out.returncode, 0, out.stderr)
        lines = out.stdout.splitlines()
        self.assertEqual(lines[0], "trials in both: 4 (only in A: 1, only in B: 1)")
        self.assertEqual(lines[1], "A: stable 2, slipped 1, in_collision 1, missed 1")
        self.assertEqual(lines[2], "B: slipped 2, in_collision 1, dropped 1, stable 1")
        self.assertEqual(lines[3],
                         "verdicts that differ: 3 (stable -> slipped 2, slipped -> dropped 1)")
        self.assertEqual(lines[4], "  s1/m/g1: stable -> slipped")
        self.assertEqual(lines[5], "simulated time: A 3.8 s, B 3.5 s")

    def test_reads_version_3_records_spanning_lines_and_older_escapes(self):
        # Version 3 (RFC 4180): a key with a comma, a quote and a line break, details over
        # several lines (CR LF too); version 2: the same keys with backslash escapes.
        a = self.write("a.csv", HEADER +
                       'plain/x,"m,1","g ""q""\nnext",0,stable,1,0,0,0,1,1.5,"a\nb\r\nc"\n' +
                       'plain/x,m,"back\\slash",0,missed,3,0,0,0,1,0.5,"x\ny"\n')
        b = self.write("b.csv", "# visgrab trials 2\n" + HEADER +
                       'plain/x,"m,1","g ""q""\\nnext",0,slipped,1,0,0,0,1,1.5,"a\\nb"\n' +
                       'plain/x,m,"back\\\\slash",0,missed,3,0,0,0,1,0.5,""\n')
        out = self.run_script(a, b, "--list", "5")
        self.assertEqual(out.returncode, 0, out.stderr)
        lines = out.stdout.splitlines()
        self.assertEqual(lines[0], "trials in both: 2 (only in A: 0, only in B: 0)")
        self.assertEqual(lines[3], "verdicts that differ: 1 (stable -> slipped 1)")
        self.assertEqual(lines[4], '  plain/x/m,1/g "q"')
        self.assertEqual(lines[5], "next: stable -> slipped")
        self.assertEqual(lines[6], "simulated time: A 2.0 s, B 2.0 s")

    def test_line_numbers_are_where_records_start(self):
        good = self.write("good.csv", HEADER + row("s1", "g1", "stable", 1.5))
        # The first record spans lines 2-4: the repeated trial starts on line 5.
        twice = self.write("twice.csv", HEADER +
                           's1,m,g1,0,stable,1,0,0,0,1,1.5,"one\ntwo\nthree"\n' +
                           row("s1", "g1", "missed", 1))
        short = self.write("short.csv", HEADER + 's1,m,g1,0,stable,1,"x\ny"\n')
        for path, message in [(twice, "twice.csv:5: trial s1/m/g1 appears twice"),
                              (short, "short.csv:2: wrong number of fields (expected 12)")]:
            out = self.run_script(good, path)
            self.assertEqual(out.returncode, 1, path)
            self.assertIn(message, out.stderr)

    def test_identical_runs_differ_nowhere(self):
        a = self.write("a.csv", HEADER + row("s1", "g1", "stable", 1.5))
        out = self.run_script(a, a)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("verdicts that differ: 0\n", out.stdout)

    def test_bad_files_name_file_and_line(self):
        good = self.write("good.csv", HEADER + row("s1", "g1", "stable", 1.5))
        no_outcome = self.write("no_outcome.csv", "# c\nscene,method,grasp,simulated_time\n")
        twice = self.write("twice.csv", HEADER + row("s1", "g1", "stable", 1) +
                           row("s1", "g1", "missed", 1))
        not_number = self.write("nan.csv", HEADER + row("s1", "g1", "stable", "soon"))
        cases = [
            (no_outcome, "no_outcome.csv:2: expected a trials.csv header"),
            (twice, "twice.csv:3: trial s1/m/g1 appears twice"),
            (not_number, "nan.csv:2: simulated_time 'soon' is not a number"),
            (os.path.join(self.dir.name, "absent.csv"), "absent.csv: cannot read"),
        ]
        for path, message in cases:
            out = self.run_script(good, path)
            self.assertEqual(out.returncode, 1, path)
            self.assertIn(message, out.stderr)

    def test_usage_mistakes_exit_2(self):
        self.assertEqual(self.run_script("only-one.csv").returncode, 2)
        a = self.write("a.csv", HEADER)
        self.assertEqual(self.run_script(a, a, "--list", "-1").returncode, 2)


if __name__ == "__main__":
    unittest.main()
