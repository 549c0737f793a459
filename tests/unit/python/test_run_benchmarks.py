#!/usr/bin/env python3
"""Unit tests of bench/run_benchmarks.py's bookkeeping (run by CTest as Bench.Harness).

Oracles: hand-computed derived columns from a synthetic run_summary.json, and the case-file
overrides of --set checked key by key. Units: times in s.
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "bench"))
import run_benchmarks as rb  # noqa: E402


class Settings(unittest.TestCase):
    def test_values_are_typed(self):
        self.assertEqual(rb.parse_setting("contact.penetration_tolerance=1e-7"),
                         (["contact", "penetration_tolerance"], 1e-7))
        self.assertEqual(rb.parse_setting("loading.steps=32"), (["loading", "steps"], 32))
        self.assertEqual(rb.parse_setting("loading.unload=false"), (["loading", "unload"], False))
        self.assertEqual(rb.parse_setting("solver.linear_solver = direct"),
                         (["solver", "linear_solver"], "direct"))

    def test_malformed_settings_are_refused(self):
        for text in ("loading.steps", "=3", "loading..steps=3", "loading.steps="):
            with self.assertRaises(ValueError, msg=text):
                rb.parse_setting(text)

    def test_overrides_reach_the_case_and_leave_the_definitions_alone(self):
        original = rb.CASES["j2_12"][1]["loading"]["steps"]
        case = {"loading": {"steps": 64, "unload": True}}
        rb.apply_settings(case, [(["loading", "steps"], 8),
                                 (["contact", "penetration_tolerance"], 1e-7)])
        self.assertEqual(case, {"loading": {"steps": 8, "unload": True},
                                "contact": {"penetration_tolerance": 1e-7}})
        self.assertEqual(rb.CASES["j2_12"][1]["loading"]["steps"], original)
        with self.assertRaises(ValueError):
            rb.apply_settings(case, [(["loading", "steps", "x"], 1)])


class SummaryColumns(unittest.TestCase):
    def test_derived_columns(self):
        summary = {"newton_iterations": 100, "linear_solves": 80, "time_total_s": 65.0,
                   "time_setup_s": 3.0, "time_output_s": 2.0, "time_linear_solve_s": 24.0,
                   "force_at_max_depth_mN": 815.8, "cells": 10}
        row = rb.summary_columns(summary)
        self.assertAlmostEqual(row["time_per_newton_s"], 0.6)  # (65 - 3 - 2) / 100
        self.assertAlmostEqual(row["newton_over_linear_solve"], 2.0)  # 0.6 / (24 / 80)
        self.assertEqual(row["force_or_stress"], 815.8)
        self.assertEqual(row["cells"], 10)

    def test_no_newton_iterations_no_derived_columns(self):
        row = rb.summary_columns({"final_true_stress_GPa": 0.37})
        self.assertEqual(row["force_or_stress"], 0.37)
        self.assertNotIn("time_per_newton_s", row)


if __name__ == "__main__":
    unittest.main()
