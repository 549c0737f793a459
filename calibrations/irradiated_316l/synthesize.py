"""The synthetic "measurements" of the example calibration (calibrate.yaml): the hardness-depth
profile of a run (its hardness_depth.csv) written as an instrument exports it, depth in nm and
hardness in MPa, with Gaussian scatter of RELATIVE_NOISE times each hardness (seeded).

Usage: synthesize.py RUN_DIRECTORY OUT_CSV SEED RELATIVE_NOISE
Made with (from this folder, after `indentsim run pristine.yaml --output truth_pristine` and the
same for irradiated.yaml, at the case files' values):
  python3 synthesize.py truth_pristine measured_pristine_csm.csv 11 0.02
  python3 synthesize.py truth_irradiated measured_irradiated_csm.csv 12 0.02
Units: the run's um and GPa in, nm and MPa out."""
import csv
import sys

import numpy as np


def main():
    run, target, seed, noise = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    rng = np.random.default_rng(seed)
    with open(f"{run}/hardness_depth.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    with open(target, "w", newline="") as f:
        f.write("# Synthetic (synthesize.py %s, seed %d, scatter %g): not a measurement\n"
                % (run.rstrip("/").split("/")[-1], seed, noise))
        f.write("Displacement (nm),Hardness (MPa)\n")
        for row in rows:
            hardness = float(row["hardness_GPa"]) * (1 + noise * rng.standard_normal())
            f.write("%.1f,%.1f\n" % (1000 * float(row["depth_um"]), 1000 * hardness))


if __name__ == "__main__":
    main()
