// Oliver-Pharr analysis of an indentation load-penetration curve with unloading.
// Units: depths um, forces mN, areas um^2, stiffness mN/um, hardness and moduli GPa
// (1 GPa*um^2 = 1 mN), work mN*um (= nJ).
//
// W.C. Oliver, G.M. Pharr, J. Mater. Res. 7 (1992) 1564-1583, and their 2004 review
// (J. Mater. Res. 19, 3-20):
//   unloading fit      P = alpha (h - h_f)^m           (eq. 9 of 2004, on the upper unloading)
//   stiffness          S = dP/dh at h_max = alpha m (h_max - h_f)^(m - 1)
//   contact depth      h_c = h_max - epsilon P_max / S  (eq. 11; epsilon 0.72 cone, 0.75
//                                                        paraboloid/Berkovich, 1 flat punch)
//   area               A = A(h_c), the indenter's area function
//   hardness           H = P_max / A
//   reduced modulus    E_r = sqrt(pi) / (2 beta) S / sqrt(A)   (eq. 1 and 8)
//   sample modulus     1/E_r = (1 - nu^2)/E + (1 - nu_i^2)/E_i (rigid indenter: E_i = inf)
// and the work split W_t = int_loading P dh, W_e = int_unloading P dh, W_p = W_t - W_e.
//
// Independent of the finite-element code: it reads a curve (ours or a measured one), so the
// same numbers come out for simulation and experiment.
#pragma once

#include "io/LoadCurveCsv.h"

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace indentsim::analysis
{
  // The curve and its CSV reader live in io/LoadCurveCsv.h (the case reader checks a measured
  // curve too); they are used here under their analysis names.
  using io::LoadCurve;
  using io::read_load_curve_csv;
  using io::without_partial_unloads;

  // The checks of analyze() on the curve and its results (user guide, "Oliver-Pharr analysis").
  // At least this many unloading points in the fit range: the fit has 3 parameters, and 2 more
  // points leave a residual that measures how well a power law describes the unloading.
  inline constexpr unsigned int min_fit_points = 5;
  // Depth reversals up to this fraction of the depth range (max - min depth) are measurement
  // noise; a larger one is a row out of order (or, on the unloading, a reload).
  inline constexpr double depth_noise_fraction = 1e-3;
  // The unloading exponent of an elastic contact (Sneddon; Oliver and Pharr 1992, 2004): m = 1
  // for a flat punch, 1.5 for a paraboloid, 2 for a cone, 1 + 1/n for a profile z ~ r^n; a real
  // tip lies between flat punch and cone. The bound leaves 0.5 for the correlation of m with h_f
  // in the fit (the fit itself keeps m >= 1).
  inline constexpr double max_physical_exponent = 2.5;
  // W_p/W_t may fall below 0 by this much on an elastic curve (trapezoid rule on coarse steps).
  inline constexpr double work_ratio_tolerance = 0.02;

  // P = alpha (h - h_f)^m on the fitted points.
  struct PowerLawFit
  {
    double       alpha = 0;     // [mN/um^m]
    double       h_f = 0;       // [um]
    double       m = 0;         // [-]
    double       rms_error = 0; // root-mean-square force residual [mN]
    unsigned int n_points = 0;

    double force(double h) const;     // [mN]
    double stiffness(double h) const; // dP/dh [mN/um]
  };

  // Least-squares fit of P = alpha (h - h_f)^m, h_f < min(h), 1 <= m <= 6: a profile search
  // over h_f (log-linear start) polished by Levenberg-Marquardt in the force residual. Throws
  // std::invalid_argument with fewer than 3 points or non-positive forces.
  PowerLawFit fit_power_law(const std::vector<double> &depth, const std::vector<double> &force);

  struct OliverPharrSettings
  {
    double                epsilon = 0.75;  // geometry factor of the contact depth [-]
    double                beta = 1.0;      // correction factor of the modulus formula [-]
    double                fit_lower = 0.5; // fit the unloading points with P >= fit_lower P_max ...
    double                fit_upper = 1.0; // ... and P <= fit_upper P_max [-]
    std::optional<double> sample_poisson_ratio; // nu: gives the sample's Young modulus
    double                indenter_modulus = std::numeric_limits<double>::infinity(); // E_i [GPa]
    double                indenter_poisson_ratio = 0.07;                              // nu_i [-]
    // A simulated curve's recorded contact area below this [um^2] is not resolved by its mesh
    // (a contact radius under one contact element, pi h_e^2): no comparison with the true area.
    double min_true_contact_area = 0;
  };

  struct OliverPharrResult
  {
    double                max_depth = 0; // h_max [um]
    double                max_force = 0; // P_max [mN] (the force at h_max)
    PowerLawFit           fit;
    double                stiffness = 0;          // S [mN/um]
    double                contact_depth = 0;      // h_c [um]
    double                contact_area = 0;       // A(h_c) [um^2]
    double                hardness = 0;           // H [GPa]
    double                reduced_modulus = 0;    // E_r [GPa]
    std::optional<double> sample_modulus;         // E [GPa], if the sample's nu is given
    double                residual_depth = 0;     // h_r [um]: zero force after unloading
    std::string           residual_depth_source;  // "curve" (reached zero force) or "fit h_f"
    double                total_work = 0;         // W_t [mN um]
    double                elastic_work = 0;       // W_e [mN um]
    double                plastic_work_ratio = 0; // W_p / W_t [-]
    // From the simulation only: the true projected contact area at h_max, its hardness and the
    // Oliver-Pharr area's error against it (> 0: the method overestimates the area).
    std::optional<double> true_contact_area;   // [um^2]
    std::optional<double> true_hardness;       // [GPa]
    std::optional<double> area_error_percent;  // 100 (A - A_true) / A_true
    std::string           true_area_note;      // why there is no true-area comparison, or
    unsigned int          unloading_begin = 0; // index of h_max in the curve
    unsigned int          unloading_end = 0;   // one past the last unloading point
  };

  // The contact depth, area, hardness and reduced modulus at a point (h, P) whose unloading
  // stiffness S is known (eq. 11, 1 and 8 of the 2004 review): h_c = h - epsilon P / S,
  // A = A(h_c), H = P / A, E_r = sqrt(pi) / (2 beta) S / sqrt(A). With h_c <= 0 the area and
  // what follows from it stay 0 (the caller refuses it).
  struct ContactEstimate
  {
    double contact_depth = 0;   // [um]
    double contact_area = 0;    // [um^2]
    double hardness = 0;        // [GPa]
    double reduced_modulus = 0; // [GPa]
  };
  ContactEstimate contact_estimate(double depth, double force, double stiffness,
                                   const std::function<double(double)> &area_function,
                                   const OliverPharrSettings           &settings);

  // The unloading branch is the one that starts at the largest depth (the last cycle's
  // maximum; a hold ends there) and runs while the depth falls, until the force reaches zero
  // (later rows are ignored) or the curve reloads. `area_function` maps a contact depth [um] to
  // a projected area [um^2]. The curve is checked before the fit, in its recorded order (it is
  // never re-sorted): two rows out of order on the loading or the unloading (a depth reversal
  // beyond depth_noise_fraction of the depth range that is undone at the next row), a first
  // row deeper than the end of the unloading (a file in reverse order), fewer than
  // min_fit_points unloading points in the fit range; and the results are checked against the
  // bounds of an indentation: 1 <= m <= max_physical_exponent, 0 <= h_c <= h_max,
  // 0 <= h_r <= h_max, 0 <= W_p/W_t <= 1 (within work_ratio_tolerance). Any of these throws
  // std::invalid_argument naming curve.source, the row (LoadCurve::row_name), the values and
  // the rule: nothing outside the bounds is returned.
  OliverPharrResult analyze(const LoadCurve                     &curve,
                            const std::function<double(double)> &area_function,
                            const OliverPharrSettings           &settings);

  // The JSON document written as oliver_pharr.json (keys with units in their names), with the
  // curve itself (um, mN) for the plot if `curve` is given.
  std::string to_json(const OliverPharrResult &result, const OliverPharrSettings &settings,
                      const std::string &indenter_description, const std::string &source,
                      const LoadCurve *curve = nullptr);

  // The geometry factor epsilon of Oliver and Pharr for an indenter shape name.
  double default_epsilon(const std::string &shape);
} // namespace indentsim::analysis
