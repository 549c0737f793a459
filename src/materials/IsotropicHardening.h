// Isotropic hardening laws of the J2 model: the flow stress sigma_y(eps_p) against the
// equivalent plastic strain eps_p (= gamma_p of J2Plasticity.h) and its slope
// h = d sigma_y / d eps_p. Units: stresses and moduli in GPa, strains dimensionless.
//
//   linear: sigma_y = sigma_y0 + H eps_p                              (the paper's eq. 5)
//   power:  sigma_y = sigma_y0 (1 + E eps_p / sigma_y0)^n, 0 <= n < 1 (Dao et al., Acta Mater.
//           49 (2001) 3899, eqs 1-2, with the plastic strain: sigma_y0 + E eps_p is the
//           stress on the elastic line continued to the total strain; n = 0 is perfect
//           plasticity, and h(0) = E n)
//   voce:   sigma_y = sigma_y0 + Q (1 - exp(-b eps_p)) + H eps_p     (Voce 1948, with an optional
//           linear term; h(0) = Q b + H, h(inf) = H)
//   table:  piecewise linear through (eps_p,i, sigma_i), eps_p,0 = 0 < eps_p,1 < ..., sigma_0 =
//           sigma_y0 <= sigma_1 <= ...; beyond the last point continued with the last segment's
//           slope (a table that ends flat stays flat).
//
// Every law is non-decreasing (h >= 0), which makes the J2 yield residual strictly decreasing in
// the plastic multiplier, so its root is unique and bracketed (J2Plasticity.cc). Below eps_p = 0,
// which only a local Newton iterate may visit, every law continues as the tangent line at 0, so
// that the power law stays finite there.
//
// Linear and table laws are piecewise linear: the J2 return mapping solves them segment by
// segment (segment(), segment_line()), each a smooth linear-hardening problem; the kinks are
// never inside a Newton iteration.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace indentsim::materials
{
  // An invalid parameter of a law: `parameter` is its name (yield_stress, hardening_modulus,
  // young_modulus, exponent, saturation, rate, plastic_strain, stress), `detail` the value and
  // what is allowed.
  class InvalidHardeningParameter : public std::invalid_argument
  {
  public:
    InvalidHardeningParameter(const std::string &parameter_name, const std::string &what_is_wrong)
      : std::invalid_argument("IsotropicHardening: " + what_is_wrong)
      , parameter(parameter_name)
      , detail(what_is_wrong)
    {
    }
    std::string parameter;
    std::string detail;
  };

  class IsotropicHardening
  {
  public:
    enum class Law
    {
      linear,
      power,
      voce,
      table
    };

    // sigma_y and h at one plastic strain.
    struct FlowStress
    {
      double stress; // sigma_y [GPa]
      double slope;  // h = d sigma_y / d eps_p [GPa], the right derivative at a table point
    };

    // The laws above; each throws InvalidHardeningParameter naming the parameter, its value and
    // what is allowed.
    static IsotropicHardening linear(double yield_stress, double hardening_modulus);
    static IsotropicHardening power(double yield_stress, double young_modulus, double exponent);
    static IsotropicHardening voce(double yield_stress, double saturation, double rate,
                                   double hardening_modulus = 0.0);
    // At least 2 points; plastic_strain starts at 0 and increases strictly, stress is positive
    // and non-decreasing.
    static IsotropicHardening table(std::vector<double> plastic_strain, std::vector<double> stress);

    Law law() const { return kind; }

    // sigma_y0 = sigma_y(0).
    double initial_yield_stress() const { return yield_stress; }

    FlowStress evaluate(double eps_p) const;
    double     flow_stress(double eps_p) const { return evaluate(eps_p).stress; }
    double     slope(double eps_p) const { return evaluate(eps_p).slope; }

    bool piecewise_linear() const { return kind == Law::linear || kind == Law::table; }

    // Piecewise-linear laws: n_segments() segments; segment k is the line through table points
    // k and k + 1 (k = 0 is continued below eps_p = 0, the last one beyond the table); the
    // linear law is one segment.
    unsigned int n_segments() const;
    // The segment holding eps_p (at a table point the one that starts there).
    unsigned int segment(double eps_p) const;
    // The start eps_p,k of segment k (0 for k = 0: its line also holds below 0).
    double segment_start(unsigned int k) const;
    // The end eps_p,k+1 of segment k (infinity for the last).
    double segment_end(unsigned int k) const;
    // Segment k's line sigma_y = stress + slope (eps - eps_p) evaluated at eps_p.
    FlowStress segment_line(unsigned int k, double eps_p) const;

  private:
    IsotropicHardening() = default;

    Law                 kind = Law::linear;
    double              yield_stress = 0;      // sigma_y0 [GPa]
    double              hardening_modulus = 0; // H [GPa] (linear, voce)
    double              young_modulus = 0;     // E [GPa] (power)
    double              exponent = 0;          // n (power)
    double              saturation = 0;        // Q [GPa] (voce)
    double              rate = 0;              // b (voce)
    std::vector<double> table_strain;          // eps_p,i (table)
    std::vector<double> table_stress;          // sigma_i [GPa] (table)
    std::vector<double> table_slope;           // (sigma_i+1 - sigma_i)/(eps_i+1 - eps_i) [GPa]

    FlowStress evaluate_nonnegative(double eps_p) const;
  };
} // namespace indentsim::materials
