#!/usr/bin/env python3
"""tools/hard-variants draws what it says: jumps within one frame to places
up to 1 m away and back, the limits doubled only in their family, five
puppets in theirs, thrown particles within 40 m/s with rods that stay rigid,
the same scene from the same seed, and never the base's pinned hash.
Usage: test_hard_variants.py SOURCE_ROOT"""

import importlib.machinery
import importlib.util
import math
import os
import re
import sys
import unittest

ROOT = sys.argv.pop(1) if len(sys.argv) > 1 else os.getcwd()
_PATH = os.path.join(ROOT, "tools", "hard-variants", "hard-variants")
_LOADER = importlib.machinery.SourceFileLoader("hard_variants", _PATH)
_SPEC = importlib.util.spec_from_loader("hard_variants", _LOADER)
hv = importlib.util.module_from_spec(_SPEC)
_LOADER.exec_module(hv)

NUM = r"(-?[0-9.]+)"
KEY = re.compile(r"- \{t: %s, position: \[%s, %s, %s\], rotation: \[%s, %s, %s\]\}" % ((NUM,) * 7))
VEL = re.compile(r"\{name: (\w+), position: \[([^]]*)\], velocity: \[([^]]*)\]")


def keyframes(text):
    return [[float(g) for g in m.groups()] for m in KEY.finditer(text)]


class Jumps(unittest.TestCase):
    def check_jumps(self, family, puppets, level):
        text = hv.variant(family, 7)
        keys = keyframes(text)
        self.assertEqual(len(keys), 4 * puppets)
        for p in range(puppets):
            out, away, held, back = keys[4 * p:4 * p + 4]
            self.assertAlmostEqual(away[0] - out[0], 1 / 60, places=3)
            self.assertAlmostEqual(back[0] - held[0], 1 / 60, places=3)
            self.assertGreater(held[0], away[0])
            self.assertLess(back[0], 4.0)  # within the case's 4 s
            self.assertEqual(out[1:], [0.0, 1.25, 0.0, 0.0, 0.0, 0.0])
            self.assertEqual(back[1:], out[1:])
            self.assertEqual(away[1:], held[1:])
            self.assertLessEqual(abs(away[1]), 1.0)
            self.assertLessEqual(abs(away[3]), 1.0)
            self.assertLessEqual(abs(away[2] - 1.25), 0.3)
            self.assertGreater(math.dist(away[1:4], out[1:4]), 0.0)
            if level:
                self.assertEqual((away[4], away[6]), (0.0, 0.0))
        return text

    def test_jumps_turn_about_any_axis(self):
        text = self.check_jumps("jumps", 3, False)
        tilts = [abs(k[4]) + abs(k[6]) for k in keyframes(text)]
        self.assertGreater(max(tilts), 0.0)
        self.assertIn("max_speed: 20", text)

    def test_level_bars_turn_about_the_vertical_only(self):
        self.check_jumps("level", 3, True)

    def test_limits_are_doubled_in_their_family_only(self):
        text = self.check_jumps("limits", 3, False)
        self.assertEqual(text.count("max_speed: 40"), 3)
        self.assertEqual(text.count("max_turn_rate: 2880"), 3)
        self.assertNotIn("max_speed: 20", text)

    def test_five_puppets_all_jump(self):
        text = self.check_jumps("five", 5, False)
        for name in ("alice", "bob", "carol", "dave", "erin"):
            self.assertIn("- name: %s\n" % name, text)
        self.assertIn("offset: [-0.25, 0, 0.03]", text)


class Thrown(unittest.TestCase):
    def test_particles_within_40_m_s_and_rods_rigid(self):
        moving, spinning = 0, 0
        for seed in range(1, 40):
            text = hv.variant("thrown", seed)
            found = VEL.findall(text)
            self.assertEqual(len(found), 9)
            vel = {}
            for i, (name, pos, v) in enumerate(found):
                v = [float(c) for c in v.split(",")]
                self.assertLessEqual(math.hypot(*v), 40.0 + 1e-3)
                moving += math.hypot(*v) > 1.0
                vel[i] = ([float(c) for c in pos.split(",")], v)
            for a, b in ((0, 1), (2, 3), (4, 5), (6, 7)):  # the rods' two ends
                axis = [q - p for p, q in zip(vel[a][0], vel[b][0])]
                rel = [q - p for p, q in zip(vel[a][1], vel[b][1])]
                self.assertAlmostEqual(sum(x * y for x, y in zip(axis, rel)), 0.0, places=3)
                spinning += math.hypot(*rel) > 1.0
        self.assertGreater(moving, 9 * 39 * 0.9)
        self.assertGreater(spinning, 4 * 39 * 0.8)

    def test_each_seed_draws_anew(self):
        self.assertNotEqual(hv.variant("thrown", 1), hv.variant("thrown", 2))
        with open(hv.THROWN, encoding="utf-8") as f:
            base = VEL.findall(f.read())
        drawn = VEL.findall(hv.variant("thrown", 1))
        for (_, _, was), (_, _, now) in zip(base, drawn):
            self.assertNotEqual([float(c) for c in was.split(",")],
                                [float(c) for c in now.split(",")])


class Files(unittest.TestCase):
    def test_same_seed_same_scene_and_no_pinned_hash(self):
        for family in hv.FAMILIES:
            a = hv.variant(family, 11)
            self.assertEqual(a, hv.variant(family, 11))
            self.assertNotEqual(a, hv.variant(family, 12))
            self.assertNotIn("state_hash", a)
            self.assertIn("max_penetration: 0.0011", a)
            self.assertIn("resets: 0", a)
            self.assertIn("family %s, seed 11" % family, a)


if __name__ == "__main__":
    unittest.main()
