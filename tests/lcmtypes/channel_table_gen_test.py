#!/usr/bin/env python3
"""lcmtypes/channel_table_gen.py on small .lcm files: a channel line reaches
the table with its suffix and default prefix; a malformed one, a second
struct on the same channel name and a line outside a struct are refused
naming the file and line."""
import os
import subprocess
import sys
import tempfile
import unittest

GEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                   "lcmtypes", "channel_table_gen.py")


class ChannelTableGen(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.dir.name, "channel_table.hpp")

    def tearDown(self):
        self.dir.cleanup()

    def lcm(self, name, channel, before=""):
        path = os.path.join(self.dir.name, name + ".lcm")
        with open(path, "w", encoding="utf-8") as f:
            f.write("package mrsim;\n" + before + "struct " + name +
                    "\n{\n  // channel: " + channel +
                    "\n  int64_t utime;\n}\n")
        return path

    def run_gen(self, *paths):
        return subprocess.run([sys.executable, GEN, "--output", self.out,
                               *paths], capture_output=True, text=True)

    def test_channels_reach_the_table_with_suffix_and_prefix(self):
        r = self.run_gen(
            self.lcm("a_t", "<prefix>_A_<robot>"),
            self.lcm("b_t", "<prefix>_B (default prefix FARM)"),
            self.lcm("c_t", "<prefix>_C_<shard>"))
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.out, encoding="utf-8") as f:
            text = f.read()
        self.assertIn('X(a_t, "a", "<prefix>_A_<robot>", "_A_", "robot", '
                      "kDefaultChannelPrefix)", text)
        self.assertIn('X(b_t, "b", "<prefix>_B", "_B", "", "FARM")', text)
        self.assertIn('X(c_t, "c", "<prefix>_C_<shard>", "_C_", "shard"', text)

    def test_a_malformed_channel_is_refused_naming_its_line(self):
        for channel in ("MRSIM_A", "<prefix>_A<robot>", "<prefix>_A_<who>",
                        "<prefix>_A (default MRSIM)"):
            path = self.lcm("a_t", channel)
            r = self.run_gen(path)
            self.assertEqual(r.returncode, 2, channel)
            self.assertIn(f"{path}:4: channel '{channel}'", r.stderr)

    def test_two_types_on_one_channel_name_are_refused(self):
        r = self.run_gen(self.lcm("a_t", "<prefix>_A"),
                         self.lcm("b_t", "<prefix>_A"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("name a already has a channel", r.stderr)

    def test_a_channel_line_outside_a_struct_is_refused(self):
        path = self.lcm("a_t", "<prefix>_A",
                        before="// channel: <prefix>_B\n")
        r = self.run_gen(path)
        self.assertEqual(r.returncode, 2)
        self.assertIn(f"{path}:2: '// channel:' outside a struct", r.stderr)


if __name__ == "__main__":
    unittest.main()
