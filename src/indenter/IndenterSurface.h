// A rigid indenter is an analytic surface behind this small interface, so that new tip shapes
// plug into the contact algorithm without touching it. Units: um.
//
// Frame: the indenter axis is z; the specimen's top face is z = 0 in the reference configuration,
// the specimen occupies z <= 0 and the indenter approaches from above. At indentation depth h the
// tip apex sits at (0, 0, -h). The surface is described in the indenter's own frame (apex at
// the origin, opening upwards: z_tip = profile(x, y) >= 0).
//
// Implementations: RoundedCone (the paper's eq. 16), and the library of rigid shapes with exact
// closest-point projection: Sphere, Cone, Pyramid (Vickers, Berkovich), FlatPunch (the rounded
// ones built by MinkowskiRounding.h) and ProfileTable (a tabulated axisymmetric profile or area
// function). IndenterFactory maps indenter.shape to them.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace indentsim::indenter
{
  using dealii::Point;
  using dealii::Tensor;

  struct SurfaceProjection
  {
    double       gap;           // signed normal gap [um]: > 0 separated, < 0 penetrating
    Point<3>     closest_point; // closest point on the indenter surface (specimen frame) [um]
    Tensor<1, 3> normal;        // unit outward normal of the indenter at closest_point,
                                // pointing from the indenter into the specimen (z-component <= 0)
    bool converged = true;      // false if the closest-point search failed
  };

  class IndenterSurface
  {
  public:
    virtual ~IndenterSurface() = default;

    // Height of the indenter surface above its apex at radial position (x, y) [um].
    virtual double profile(double x, double y) const = 0;

    // Signed distance, closest point and outward normal for a point x (specimen frame, current
    // configuration) when the apex is at depth `depth` (apex at (0,0,-depth)).
    virtual SurfaceProjection project(const Point<3> &x, double depth) const = 0;

    // Projected (horizontal cross-section) contact area of the ideal shape at depth h [um^2]:
    // the area of {(x, y): profile(x, y) < h}, 0 for h <= 0.
    virtual double projected_area(double h) const = 0;

    // True if the planes x = 0 (the yz plane) and y = 0 (the xz plane) are both mirror planes
    // of the indenter. The quarter model (specimen.symmetry: quarter, u_x = 0 on x = 0 and
    // u_y = 0 on y = 0) is exact only then: axisymmetric shapes always, a Vickers pyramid at a
    // rotation that is a multiple of 45 deg, a Berkovich pyramid never.
    virtual bool mirror_symmetric_about_xz_and_yz() const = 0;

    virtual std::string name() const = 0;
  };
} // namespace indentsim::indenter
