// The hardness-depth profile of a run with partial unloads (loading.partial_unloads), and its
// Nix-Gao plot. Units: depths um, forces mN, stiffness mN/um, areas um^2, hardness and moduli
// GPa (1 GPa*um^2 = 1 mN).
//
// Each partial unload is analysed as Oliver and Pharr analyse a full one (analysis/OliverPharr.h):
// the power law P = alpha (h - h_f)^m is fitted to the point where it starts (h, P) and its
// unloading points, S = dP/dh there, and contact_estimate gives h_c, A(h_c), H and E_r. This is
// what continuous stiffness measurement gives in an experiment, one depth at a time.
//
// Nix-Gao (W.D. Nix, H. Gao, J. Mech. Phys. Solids 46, 1998, 411-425): H^2 = H_0^2 (1 + h*/h) is a
// straight line in 1/h. Over a hardened layer on a softer substrate the line bends where the
// substrate begins to carry the plastic zone; the bilinear fit of Kasada et al. (Fusion Eng. Des.
// 86, 2011, 2658-2661) takes the shallow branch as the layer's own: its intercept H_0 is the
// layer's bulk-equivalent hardness, and the knee depth tells from where the substrate speaks.
#pragma once

#include "analysis/OliverPharr.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace indentsim::analysis
{
  // One partial unload's Oliver-Pharr analysis.
  struct HardnessPoint
  {
    double          depth = 0;             // h where the partial unload starts [um]
    double          force = 0;             // P there [mN]
    double          stiffness = 0;         // S = dP/dh of the fitted unloading at h [mN/um]
    ContactEstimate estimate;              // h_c, A(h_c), H, E_r
    double          unloaded_fraction = 0; // (P - P_end) / P: how far the force fell [-]
    PowerLawFit     fit;
    // From the simulation: the true projected contact area at h and its hardness P / A_true.
    std::optional<double> true_contact_area; // [um^2]
    std::optional<double> true_hardness;     // [GPa]
  };

  // The bilinear fit of H^2 against x = 1/h, continuous at the knee x_k:
  //   H^2 = a + b x                  for x >= x_k (shallow: the layer's branch)
  //   H^2 = a + b x + c (x_k - x)    for x <  x_k (deep: the substrate speaks)
  // The knee is searched over the intervals between the points, with at least
  // min_branch_points on either side, by least squares.
  struct NixGaoFit
  {
    double knee_depth = 0;           // 1 / x_k [um]
    double layer_hardness = 0;       // H_0 = sqrt(a): the layer's bulk-equivalent hardness [GPa]
    double layer_characteristic = 0; // h* = b / a [um]
    double deep_slope = 0;           // b - c: the deep branch's slope [GPa^2 um]
    double deep_intercept = 0;       // a + c x_k [GPa^2]
    double layer_range[2] = {0, 0};  // shallowest and deepest point of the shallow branch [um]
    double deep_range[2] = {0, 0};   // shallowest and deepest point of the deep branch [um]
    double rms = 0;                  // root-mean-square residual of H^2 [GPa^2]
    double single_line_rms = 0;      // the same of one straight line through all points
    // F = ((SSE_1 - SSE_2) / 2) / (SSE_2 / (n - 4)): how much the knee (two more parameters)
    // improves on one line. Above knee_f_threshold the knee is significant (about the 95 %
    // point of F(2, n - 4) for n >= 10; the search over the knee makes it approximate); below
    // it one line describes the points as well and the knee is arbitrary (a homogeneous
    // material).
    double f_statistic = 0;
    bool   knee_significant() const;
  };
  inline constexpr unsigned int min_branch_points = 3;
  inline constexpr double       knee_f_threshold = 4;

  // The partial unloads of `curve` (rows whose segment is partial_unload, each after the row
  // where it starts), analysed. A partial unload whose fit gives no positive stiffness or no
  // contact area is left out with a message in `skipped` (its depth and why).
  std::vector<HardnessPoint> analyze_partial_unloads(const LoadCurve                     &curve,
                                                     const std::function<double(double)> &area,
                                                     const OliverPharrSettings           &settings,
                                                     std::vector<std::string>            &skipped);

  // The bilinear Nix-Gao fit of H(h) (h: the depth where each partial unload starts), or none
  // with fewer than 2 min_branch_points points.
  std::optional<NixGaoFit> fit_nix_gao(const std::vector<double> &depth,
                                       const std::vector<double> &hardness);

  // hardness_depth.csv: one row per partial unload, the columns named with their units.
  std::string to_csv(const std::vector<HardnessPoint> &points);
  // hardness_depth.json: the points, the Nix-Gao fit (or why there is none), what was skipped.
  std::string to_json(const std::vector<HardnessPoint> &points,
                      const std::optional<NixGaoFit>   &nix_gao,
                      const std::vector<std::string> &skipped, const std::string &source);
} // namespace indentsim::analysis
