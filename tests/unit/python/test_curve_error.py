#!/usr/bin/env python3
"""Unit tests of bench/curve_error.py (run by CTest as Bench.CurveError): the error measures that
docs/validation.md and docs/performance.md quote for loading curves of the paper's J2 case.

Oracles: synthetic curves P = C (1 + e) (h + delta)^2 with a known relative error e, whose RMS
over h in [1, 6] um, of P(6.0 um), is the closed form
|e| C sqrt(((6 + delta)^5 - (1 + delta)^5) / 25) / (C (6 + delta)^2), and a curve that does not
reach 6.0 um, which must be refused. Units: um, mN, GPa.
"""

import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "bench"))
import curve_error as ce  # noqa: E402

C, DELTA = 23.065, 0.005


def synthetic(error, depths):
    return [(h, C * (1 + error) * (h + DELTA) ** 2) for h in depths]


class CurveError(unittest.TestCase):
    def test_uniform_relative_error_gives_its_closed_form(self):
        depths = [6.0 * i / 3000 for i in range(1, 3001)]
        low, high, mean, rms = ce.errors(synthetic(-0.02, depths), C, DELTA)
        self.assertAlmostEqual(low, -2.0, places=9)
        self.assertAlmostEqual(high, -2.0, places=9)
        self.assertAlmostEqual(mean, -2.0, places=9)
        closed = 2.0 * math.sqrt(((6 + DELTA) ** 5 - (1 + DELTA) ** 5) / 25) / (6 + DELTA) ** 2
        self.assertAlmostEqual(rms, closed, delta=1e-5)  # linear interpolation between points

    def test_pointwise_range_sees_a_single_dip(self):
        depths = [1.0 + 0.25 * i for i in range(21)]
        points = synthetic(0.0, depths)
        points[8] = (points[8][0], points[8][1] * 0.985)
        low, high, mean, _ = ce.errors(points, C, DELTA)
        self.assertAlmostEqual(low, -1.5, places=9)
        self.assertAlmostEqual(high, 0.0, places=9)
        self.assertAlmostEqual(mean, -1.5 / 21, places=9)

    def test_a_curve_short_of_six_um_is_refused(self):
        with self.assertRaises(ValueError):
            ce.errors(synthetic(0.0, [0.5 + 0.1 * i for i in range(50)]), C, DELTA)


if __name__ == "__main__":
    unittest.main()
