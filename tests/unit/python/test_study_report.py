#!/usr/bin/env python3
"""Unit tests of the numbers in python/study_report.py (run by CTest as StudyReport.Numbers).

Oracles are independent of the code under test: synthetic sequences F_h = F0 + C h^p with known
p and F0 (observed order, Richardson extrapolation, grid convergence index), straight lines
(interpolation, depth at a force) and hand-written Markdown (the HTML rendering).
Units: h in um, forces in mN.
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "python"))
import study_report as sr  # noqa: E402


def power_law(h_values, f0, c, p):
    return [f0 + c * h ** p for h in h_values]


class ObservedOrder(unittest.TestCase):
    """The observed order and the extrapolated value recover p and F0 of an exact power law."""

    def test_constant_ratio(self):
        h = [120.0 / 12, 120.0 / 24, 120.0 / 48]  # ratio 2
        for p in (0.5, 1.0, 2.0, 3.3):
            f = power_law(h, 821.2, -40.0, p)
            order, reason = sr.observed_order(h, f)
            self.assertIsNone(reason)
            self.assertAlmostEqual(order, p, places=10)
            self.assertAlmostEqual(sr.richardson_extrapolation(h, f, order), 821.2, places=8)

    def test_general_ratios_24_48_72(self):
        h = [120.0 / 24, 120.0 / 48, 120.0 / 72]  # ratios 2 and 1.5
        for p, c in ((1.7, -35.0), (1.0, 12.0), (2.4, 0.8)):
            f = power_law(h, 822.2, c, p)
            order, reason = sr.observed_order(h, f)
            self.assertIsNone(reason)
            self.assertAlmostEqual(order, p, places=8)
            self.assertAlmostEqual(sr.richardson_extrapolation(h, f, order), 822.2, places=6)

    def test_grid_convergence_index(self):
        # For an exact power law F_ext = F0, so GCI = 1.25 |F0 - F3| / |F3|.
        h = [5.0, 2.5, 120.0 / 72]
        f = power_law(h, 830.0, -20.0, 2.0)
        order, _ = sr.observed_order(h, f)
        self.assertAlmostEqual(sr.grid_convergence_index(h, f, order),
                               1.25 * abs(830.0 - f[2]) / abs(f[2]), places=10)

    def test_non_monotone_sequences_have_no_order(self):
        h = [10.0, 5.0, 2.5]
        order, reason = sr.observed_order(h, [821.6, 723.6, 814.9])  # the README's crystal (001)
        self.assertIsNone(order)
        self.assertIn("oscillatory", reason)
        order, reason = sr.observed_order(h, [800.0, 801.0, 803.0])  # differences grow
        self.assertIsNone(order)
        order, reason = sr.observed_order(h, [800.0, 810.0, 810.0])
        self.assertIsNone(order)
        with self.assertRaises(ValueError):
            sr.observed_order([2.5, 5.0, 10.0], [1.0, 2.0, 3.0])

    def test_constant_ratio_triples(self):
        h = [120.0 / n for n in (12, 24, 48, 72)]
        self.assertEqual(sr.constant_ratio_triples(h), [(0, 1, 2)])


class Interpolation(unittest.TestCase):
    """Linear interpolation and the depth at which a loading curve reaches a force."""

    def test_interpolate(self):
        self.assertAlmostEqual(sr.interpolate(0.05, [0.0, 0.1, 0.2], [0.0, 0.3, 0.4]), 0.15)
        self.assertAlmostEqual(sr.interpolate(0.2, [0.0, 0.1, 0.2], [0.0, 0.3, 0.4]), 0.4)
        self.assertIsNone(sr.interpolate(0.3, [0.0, 0.1, 0.2], [0.0, 0.3, 0.4]))

    def test_depth_at_force(self):
        depth = [0.0, 1.0, 2.0, 3.0, 4.0]
        force = [100.0 * d for d in depth]  # F = 100 d
        self.assertAlmostEqual(sr.depth_at_force(depth, force, 250.0), 2.5)
        self.assertAlmostEqual(sr.depth_at_force(depth, force, 400.0), 4.0)
        self.assertIsNone(sr.depth_at_force(depth, force, 401.0))

    def test_spread(self):
        low, high, mean, relative = sr.spread([814.9, 832.1])
        self.assertEqual((low, high), (814.9, 832.1))
        self.assertAlmostEqual(relative, (832.1 - 814.9) / 823.5)


class Html(unittest.TestCase):
    """The Markdown subset of the report renders to HTML tables, images, links and headings."""

    def test_rendering(self):
        page = sr.markdown_to_html("# Title\n\ntext with `code` and **bold**\n\n"
                                   "| a [mN] | b |\n|---|---|\n| 1 | [x](y.yaml) |\n\n"
                                   "![fig](figures/f.png)\n\n- item\n", "t")
        for fragment in ("<h1>Title</h1>", "<code>code</code>", "<strong>bold</strong>",
                         "<th>a [mN]</th>", "<td>1</td>", '<a href="y.yaml">x</a>',
                         '<img src="figures/f.png" alt="fig">', "<li>item</li>"):
            self.assertIn(fragment, page)
        self.assertNotIn("|---|", page)


class CurveDifference(unittest.TestCase):
    """The RMS and largest difference of two curves, for a difference linear in the depth (so
    that the linear interpolation is exact): c h at h = 0, 1/4, ..., 1 has the RMS
    c sqrt(mean h^2) = c sqrt(0.375) and the largest value c."""

    def test_linear_difference(self):
        c = 3.0
        ref_depth = [0.0, 0.25, 0.5, 0.75, 1.0]
        ref_force = [100.0 * h for h in ref_depth]
        depth = [0.0, 0.5, 1.0]  # coarser sampling of 100 h + c h
        force = [(100.0 + c) * h for h in depth]
        rms, largest, n = sr.curve_difference(ref_depth, ref_force, depth, force)
        self.assertEqual(n, 5)
        self.assertAlmostEqual(rms, c * 0.375 ** 0.5, places=12)
        self.assertAlmostEqual(largest, c, places=12)

    def test_only_the_overlap_counts(self):
        rms, largest, n = sr.curve_difference([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 2.0, 3.0],
                                              [1.0, 2.0], [2.0, 3.0])
        self.assertEqual(n, 2)
        self.assertAlmostEqual(rms, 1.0, places=12)
        self.assertEqual(sr.curve_difference([5.0], [1.0], [0.0, 1.0], [0.0, 1.0]), (None, None, 0))


if __name__ == "__main__":
    unittest.main()
