// An axisymmetric indenter given by a table (indenter.shape: profile_table), either as its
// profile or as its area function, read from a CSV file. Units: um.
//
// File format (comma-separated; blank lines and lines starting with '#' are skipped; the first
// other line is the header, every further line one row of two numbers):
//   r_um,z_um           the profile: height z above the apex at the distance r from the axis;
//                       the first row is the apex 0,0, r strictly increasing, z non-decreasing;
//   depth_um,area_um2   the area function A(h) that experimentalists calibrate; the first row is
//                       0,0, both columns strictly increasing. It is converted to the equivalent
//                       axisymmetric profile through r(h) = sqrt(A(h) / pi), z = h.
// At least 2 rows, and the last two rows must differ in z (depth), because beyond the table the
// profile continues as a straight line with the last slope.
//
// Interpolation: monotone piecewise-cubic Hermite (PCHIP; Fritsch and Carlson 1980, with the
// weighted harmonic-mean slopes of Fritsch and Butland 1984 as in SciPy's PchipInterpolator)
// of z(r). It is C1, so the surface normal is continuous, it never overshoots the data (a
// non-decreasing table gives a non-decreasing profile), and it reproduces straight lines exactly
// (an area function of a cone gives the exact cone). The slope at r = 0 is the one-sided
// three-point estimate (zero for a profile that is quadratic there, e.g. a sphere); the slope at
// the last row is the last secant slope, and the profile continues with it beyond the table.
#pragma once

#include "indenter/IndenterSurface.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace indentsim::indenter
{
  // A table file that cannot be read or is not a valid profile; the message names the file, the
  // line and what is allowed.
  class ProfileTableError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  class ProfileTable : public IndenterSurface
  {
  public:
    enum class Kind
    {
      profile,       // r_um,z_um
      area_function, // depth_um,area_um2
    };

    // Reads and validates a table file. Throws ProfileTableError.
    static ProfileTable read(const std::string &path);

    // A profile z(r) given in code (rules as for r_um,z_um). `source` names the table in
    // messages. Throws ProfileTableError.
    ProfileTable(std::vector<double> radii, std::vector<double> heights,
                 const std::string &source = "profile table");

    double profile(double x, double y) const override;

    // Exact closest point on the meridian curve: the stationary points of the squared distance
    // on every cubic piece are the roots of a quintic, all isolated by subdividing its Bernstein
    // form (Descartes' rule of signs) and refined by safeguarded Newton; pieces whose bounding box
    // is farther than the best point so far are skipped. Plus the apex and the straight
    // continuation beyond the table.
    SurfaceProjection project(const Point<3> &x, double depth) const override;

    // pi r(h)^2, r(h) the first radius where the profile reaches h; at the rows of an area
    // function exactly the tabulated areas.
    double projected_area(double h) const override;

    bool mirror_symmetric_about_xz_and_yz() const override { return true; }

    std::string name() const override { return "profile_table"; }

    Kind                       kind() const { return table_kind; }
    const std::string         &source() const { return source_name; }
    const std::vector<double> &radii() const { return r; }
    const std::vector<double> &heights() const { return z; }
    const std::vector<double> &slopes() const { return dz_dr; } // PCHIP dz/dr at the rows

    // The interpolated profile z(r) and its slope for r >= 0.
    double profile_at_radius(double radius) const;
    double slope_at_radius(double radius) const;
    // The first radius where the profile reaches h (0 for h <= 0) [um].
    double radius_at_height(double h) const;

  private:
    Kind                table_kind = Kind::profile;
    std::string         source_name;
    std::vector<double> r, z;              // rows [um]
    std::vector<double> dz_dr;             // PCHIP slopes at the rows [-]
    std::vector<double> box_low, box_high; // z range of each cubic piece (Bezier hull) [um]

    ProfileTable() = default;
    // Fills the slopes and boxes; r, z already validated.
    void build();
    // The piece index k with r[k] <= radius < r[k+1] (n_rows - 1 beyond the table).
    std::size_t piece_of(double radius) const;

    // The closest point so far of the profile to the meridian point (rho, zeta) [um].
    struct Closest
    {
      double rho = 0., zeta = 0.;
      double best = std::numeric_limits<double>::infinity(); // its distance
      double foot_r = 0., foot_z = 0.;
      void   consider(double radius, double height);
    };
    // Offers `closest` the stationary points of the distance on cubic piece k.
    void closest_on_piece(std::size_t k, Closest &closest) const;
  };
} // namespace indentsim::indenter
