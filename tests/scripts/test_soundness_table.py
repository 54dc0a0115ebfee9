#!/usr/bin/env python3
"""scripts/soundness_table.py: the runner's table filed between the soundness
markers with its "Made by" line, the text around them kept; a file that is
not the runner's table, or a page without the markers, refused."""

import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "soundness_table.py")
HEADER = "| case | checker | edges | colliding edges | missed | false alarms | median time per edge (us) |"
ROW = "| thin-wall | fcl | 200 | 166 | 33 | 0 | 3.21 |"


class SoundnessTable(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.summary = os.path.join(self.tmp.name, "summary.md")
        self.page = os.path.join(self.tmp.name, "page.md")

    def tearDown(self):
        self.tmp.cleanup()

    def run_script(self, summary, page):
        with open(self.summary, "w") as f:
            f.write(summary)
        with open(self.page, "w") as f:
            f.write(page)
        return subprocess.run([sys.executable, SCRIPT, "--input", self.summary, "--readme", self.page,
                               "--command", "run X"], capture_output=True, text=True)

    def test_files_the_table_between_the_markers(self):
        page = "before\n<!-- soundness:begin -->\nold\n<!-- soundness:end -->\nafter\n"
        result = self.run_script("%s\n|---|---|---|---|---|---|---|\n%s\n" % (HEADER, ROW), page)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.page) as f:
            text = f.read()
        self.assertTrue(text.startswith("before\n<!-- soundness:begin -->\nMade by `scripts/soundness_table.py` "
                                        "from `run X`.\n"))
        self.assertIn(HEADER + "\n|---|---|---|---|---|---|---|\n" + ROW + "\n<!-- soundness:end -->\nafter\n", text)
        self.assertNotIn("old", text)

    def test_refuses_other_input_and_a_page_without_markers(self):
        result = self.run_script("| a | b |\n", "<!-- soundness:begin -->\n<!-- soundness:end -->\n")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("header", result.stderr)
        result = self.run_script("%s\n|---|\n| a | b |\n" % HEADER, "<!-- soundness:begin -->\n<!-- soundness:end -->\n")
        self.assertIn("not a row of 7 cells", result.stderr)
        result = self.run_script("%s\n|---|---|---|---|---|---|---|\n%s\n" % (HEADER, ROW), "no markers\n")
        self.assertIn("no <!-- soundness:begin -->", result.stderr)


if __name__ == "__main__":
    unittest.main()
