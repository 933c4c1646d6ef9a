#!/usr/bin/env python3
"""lcmtypes/wire_check_gen.py on small .lcm files: a variable-length field
without its `// max:` is refused, a limits table that drifted from the
.lcm files fails --check-doc, and `// unit:` comments reach the units
table."""
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest

GEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                   "lcmtypes", "wire_check_gen.py")


def run(*args):
    return subprocess.run([sys.executable, GEN, *args], capture_output=True,
                          text=True)


class WireCheckGen(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def lcm(self, body):
        path = os.path.join(self.dir.name, "t.lcm")
        with open(path, "w", encoding="utf-8") as f:
            f.write("package mrsim;\nstruct t\n{\n" + body + "}\n")
        return path

    def test_string_without_max_is_refused_naming_its_line(self):
        path = self.lcm("  string robot;  // max: 256\n  string name;\n")
        r = run("--markdown", path)
        self.assertEqual(r.returncode, 2)
        self.assertIn(f"{path}:5: string name needs a '// max: N'", r.stderr)

    def test_length_member_without_max_is_refused(self):
        path = self.lcm("  int32_t n;\n  double v[n];\n")
        r = run("--markdown", path)
        self.assertEqual(r.returncode, 2)
        self.assertIn("length member n needs a '// max: N'", r.stderr)

    def test_every_limit_reaches_the_table(self):
        path = self.lcm("  string s;  // max: 64\n  int32_t n;  // max: 8\n"
                        "  double v[n];\n")
        r = run("--markdown", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| t | s | 64 bytes |", r.stdout)
        self.assertIn("| t | n | 8 elements (v) |", r.stdout)

    def test_units_reach_the_units_header(self):
        path = self.lcm("  double torque;  // unit: N m\n"
                        "  int32_t n;  // max: 8, unit: 1\n"
                        "  double v[n];\n")
        header = os.path.join(self.dir.name, "units.hpp")
        checks = os.path.join(self.dir.name, "wire.hpp")
        r = run("--output", checks, "--units-output", header, path)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(header, encoding="utf-8") as f:
            text = f.read()
        self.assertIn('{"mrsim.t", "torque", "N m"},', text)
        self.assertIn('{"mrsim.t", "n", "1"},', text)
        self.assertNotIn('"v"', text)
        # Unchanged text keeps the file (and whatever includes it) as it was.
        before = os.stat(header).st_mtime_ns
        os.utime(header, ns=(before - 10**9, before - 10**9))
        self.assertEqual(run("--output", checks, "--units-output", header,
                             path).returncode, 0)
        self.assertEqual(os.stat(header).st_mtime_ns, before - 10**9)

    def test_a_unit_comment_without_a_unit_is_refused(self):
        path = self.lcm("  double torque;  // unit:\n")
        r = run("--markdown", path)
        self.assertEqual(r.returncode, 2)
        self.assertIn(f"{path}:4: 'unit:' without a unit", r.stderr)

    def test_check_doc_fails_on_a_drifted_table_and_update_fixes_it(self):
        path = self.lcm("  string s;  // max: 64\n")
        doc = os.path.join(self.dir.name, "doc.md")
        table = run("--markdown", path).stdout
        spec = importlib.util.spec_from_file_location("gen", GEN)
        gen = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(gen)
        with open(doc, "w", encoding="utf-8") as f:
            f.write("intro\n" + gen.DOC_BEGIN + "\n" +
                    table.replace("64 bytes", "32 bytes") + gen.DOC_END +
                    "\nafter\n")
        r = run("--check-doc", doc, path)
        self.assertEqual(r.returncode, 1)
        self.assertIn(f"{doc}:3: the limits table differs", r.stderr)
        self.assertIn("+| t | s | 64 bytes |", r.stderr)
        self.assertEqual(run("--update-doc", doc, path).returncode, 0)
        self.assertEqual(run("--check-doc", doc, path).returncode, 0)
        with open(doc, encoding="utf-8") as f:
            text = f.read()
        self.assertTrue(text.startswith("intro\n") and text.endswith("after\n"))


if __name__ == "__main__":
    unittest.main()
