// A regular n-sided pyramid with exactly flat faces, each at the angle theta to the axis
// (Vickers: n = 4, theta = 68 deg; Berkovich: n = 3, theta = 65.27 deg), sharp or rounded by a
// ball of radius R (MinkowskiRounding.h): the faces stay flat with the exact angle, the edges
// become cylinders and the tip a sphere of radius R. The sharp pyramid serves the analysis (its
// area function); a run needs R > 0 (CaseValidator: at a sharp edge the contact normal jumps).
// Units: um.
//
// Orientation: face i (i = 0 .. n-1) has the outward normal
//   n_i = (cos(theta) cos(phi_i), cos(theta) sin(phi_i), -sin(theta)),
//   phi_i = rotation_deg + i 360/n deg,
// i.e. at rotation_deg = 0 face 0 faces +x (its normal's horizontal part points along +x); a
// positive rotation turns the indenter counterclockwise seen from above (about +z). Edge k lies
// between faces k and k+1, at the azimuth phi_k + 180/n deg. So at rotation 0 a Vickers pyramid
// has its faces towards +-x and +-y and its edges along the diagonals x = +-y; a Berkovich
// pyramid has face 0 towards +x and an edge along -x (edges at 60, 180 and 300 deg).
//
// Projected area: n tan(pi/n) tan^2(theta) h^2 for the sharp pyramid (Vickers 24.504 h^2,
// Berkovich 24.494 h^2). Rounded, for h >= R (1 - sin(theta)) exactly
//   A(h) = n tan(pi/n) tan^2(theta) (h + Delta)^2 - n D,   Delta = R (1/sin(theta) - 1),
// where Delta is how far the offset faces lie below the sharp ones and D is the area that the
// rounding of one edge cuts off the polygon's corner (see corner_deficit()).
#pragma once

#include "indenter/IndenterSurface.h"

#include <vector>

namespace indentsim::indenter
{
  class Pyramid : public IndenterSurface
  {
  public:
    static constexpr double       vickers_face_angle_deg = 68.;
    static constexpr double       berkovich_face_angle_deg = 65.27;
    static constexpr unsigned int max_faces = 16;

    // 3 <= n_faces <= max_faces, 0 < theta < 90 deg, R >= 0 [um], finite rotation [deg]; throws
    // std::invalid_argument otherwise. `name` is what name() returns.
    Pyramid(std::string name, unsigned int n_faces, double face_angle_deg, double tip_radius,
            double rotation_deg);

    static Pyramid vickers(double tip_radius, double rotation_deg);
    static Pyramid berkovich(double tip_radius, double rotation_deg);

    // Sharp: max_i of the face planes' heights; rounded: the root of the gap along the vertical
    // (Newton, monotone from below since the gap is convex and decreasing along +z).
    double profile(double x, double y) const override;

    // Exact projection onto the sharp polyhedral cone (inside: the nearest face plane; outside:
    // the nearest of the feasible face feet, the edge rays and the apex), moved by R.
    SurfaceProjection project(const Point<3> &x, double depth) const override;

    // Closed form (class comment); on the rounded tip below R (1 - sin(theta)), where the
    // cross-section consists of circular arcs (tip sphere) and elliptic arcs (edge cylinders),
    // Gauss quadrature of r(phi)^2/2 between the exact arc junctions.
    double projected_area(double h) const override;

    // x = 0 and y = 0 are mirror planes iff both are among the n mirror planes at the azimuths
    // rotation_deg + k 180/n: for Vickers when rotation_deg is a multiple of 45 deg, for
    // Berkovich never.
    bool mirror_symmetric_about_xz_and_yz() const override;

    // The number of faces whose trace on the surface runs parallel to the x or the y axis
    // (phi_i a multiple of 90 deg, to 0.5 deg): on the meshes' x-y grid lines such a face's
    // contact edge reaches a whole row of surface nodes at once (IndentationGuards.cc).
    unsigned int faces_along_axes() const;

    std::string name() const override { return shape_name; }

    unsigned int        n_faces() const { return static_cast<unsigned int>(face_normals.size()); }
    double              face_angle() const { return theta; } // [rad]
    double              tip_radius() const { return R; }
    double              rotation_deg() const { return rotation; }
    const Tensor<1, 3> &face_normal(unsigned int i) const { return face_normals[i]; }
    const Tensor<1, 3> &edge_direction(unsigned int k) const { return edge_directions[k]; }
    // n tan(pi/n) tan^2(theta): A = coefficient h^2 for the sharp pyramid.
    double sharp_area_coefficient() const;
    // Delta = R (1/sin(theta) - 1) [um].
    double blunting_offset() const;
    // D = R^2 (cot(gamma') - (pi/2 - gamma')) / cos(beta): in a horizontal section the edge
    // cylinder is an ellipse of semi-axes R / cos(beta) (radial) and R (beta: the edge's angle
    // to the axis, tan(beta) = tan(theta) / cos(pi/n)); compressing the radial direction by
    // cos(beta) makes it a circle and opens the corner's half-angle gamma = pi/2 - pi/n to
    // gamma' = atan(tan(gamma) / cos(beta)); the circle cuts R^2 (cot(gamma') - (pi/2 -
    // gamma')) off that corner [um^2].
    double corner_deficit() const;

  private:
    std::string               shape_name;
    double                    theta;
    double                    R;
    double                    rotation;
    double                    sin_theta;
    double                    edge_angle; // beta [rad]
    std::vector<Tensor<1, 3>> face_normals;
    std::vector<Tensor<1, 3>> edge_directions;

    // Height of the sharp pyramid's surface above its apex at (x, y).
    double sharp_profile(double x, double y) const;
  };
} // namespace indentsim::indenter
