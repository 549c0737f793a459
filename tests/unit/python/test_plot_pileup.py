#!/usr/bin/env python3
"""Unit tests of the pile-up map's title in python/plot_pileup.py (run by CTest as
PlotPileup.FoldTitle).

Oracle: the fields of pileup.json as the program writes them (symmetry_fold, fold_source,
dominant_fold) for the documented cases: an isotropic material under an axisymmetric indenter
(no fold, the 4 is the mesh's imprint), the crystals (011) 2, (111) 3, (001) 4.
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "python"))
import plot_pileup  # noqa: E402


class FoldTitle(unittest.TestCase):
    """The title says whether there is a fold and whether it is the crystal's or may be the mesh's."""

    def test_isotropic_axisymmetric_has_no_fold(self):
        title = plot_pileup.fold_title(
            {"dominant_fold": 4, "symmetry_fold": 0, "fold_source": "axisymmetric"})
        self.assertTrue(title.startswith("axisymmetric, no fold"), title)
        self.assertIn("mesh imprint", title)
        self.assertNotIn("4-fold (", title)

    def test_crystal_folds(self):
        self.assertEqual(plot_pileup.fold_title(
            {"dominant_fold": 8, "symmetry_fold": 2, "fold_source": "crystal"}),
            "2-fold (from the crystal)")
        self.assertEqual(plot_pileup.fold_title(
            {"dominant_fold": 4, "symmetry_fold": 3, "fold_source": "crystal"}),
            "3-fold (from the crystal)")
        self.assertEqual(plot_pileup.fold_title(
            {"dominant_fold": 4, "symmetry_fold": 4, "fold_source": "mesh_imprint_possible"}),
            "4-fold (may be the square mesh's imprint)")

    def test_file_without_source(self):
        self.assertEqual(plot_pileup.fold_title({"dominant_fold": 4, "symmetry_fold": 3}),
                         "4-fold (3-fold beyond the mesh's 4/8-fold imprint)")


if __name__ == "__main__":
    unittest.main()
