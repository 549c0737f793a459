// Pile-up analysis of the indented top surface (the paper's Fig. 7: single crystals pile up in
// 4-, 2- and 3-fold patterns on (001), (011) and (111)). Units: um, deg.
//
// Input: the quadrilateral faces of the top surface z = 0, each corner with its reference
// position (X, Y) and displacement (u_x, u_y, u_z). The indenter axis is the z axis, the apex at
// (0, 0, -depth). The surface height is h = u_z (z = 0 is the undeformed surface), seen as a
// function of the current in-plane position (x, y) = (X + u_x, Y + u_y): each quad is split into
// four triangles around its vertex average (carrying the mean corner height) in current
// coordinates and h is interpolated linearly on them. On a surface that does not fold over
// itself this is exact along the face edges and at the face centres (where the bilinear
// finite-element trace takes the corner mean) and linear in between; it reproduces a linear
// field exactly and, unlike a split into two triangles, prefers no diagonal. A point covered by
// no triangle (outside the specimen) has no height: the functions return std::nullopt there and
// the CSV files leave the cell empty (never NaN).
//
// Derived quantities (all evaluated on that interpolant):
//  - a grid of h over [-R, R]^2 in current coordinates, R = radius_factor * a_c (a_c the contact
//    radius at maximum depth), spacing min(h_min / 2, R / 50) (h_min the smallest surface edge);
//  - radial profiles h(r) along given azimuths theta (x = r cos theta, y = r sin theta);
//  - the analysis radius r_c: among the circles a_c < r <= R fully covered by the surface, the one
//    with the largest azimuthal mean of h (the crest of the pile-up ring);
//  - the angular Fourier spectrum of h on the circle r_c from M equally spaced samples
//    theta_j = 2 pi j / M: c_k = (1/M) sum_j h_j exp(-i k theta_j); reported as cosine amplitudes
//    A_0 = c_0 (the mean height on the circle) and A_k = 2 |c_k| (k >= 1), so that
//    h(theta) = A_0 + sum_k A_k cos(k theta - phi_k);
//  - the dominant fold n = argmax_{k >= 2} A_k, or 0 when no harmonic rises above the noise level
//    max(1e-3 |A_0|, 1e-6 um) (an axisymmetric pile-up);
//  - the symmetry fold: the largest harmonic k >= 2 that is not a multiple of 4 when it is above
//    the noise level and at least 10 % of the largest harmonic, else the dominant fold. The
//    tensor-product mesh has the square's symmetry and imprints only k = 4, 8, 12 on a pile-up
//    (on coarse meshes as strongly as the (011) 2-fold or the (111) 3-fold pattern itself), so
//    a significant harmonic outside that set is the material's or the indenter's; a pattern
//    with none is compatible with the square ((001), a Vickers pyramid);
//  - the fold's source (SymmetrySources: what besides the mesh can break the axial symmetry).
//    An isotropic material under an axisymmetric indenter has no fold: if no harmonic beyond
//    the mesh imprint (k not a multiple of 4) stands above the noise level, the symmetry fold
//    is 0 and the source "axisymmetric", whatever the imprint's size; one that does is a
//    numerical asymmetry ("numerical"). Otherwise the source is "crystal", "indenter" or
//    "crystal_or_indenter" for a fold that is not a multiple of 4, "mesh_imprint_possible" for
//    one that is (the crystal's or pyramid's 4-fold and the mesh's imprint cannot be told apart
//    on one mesh), "axisymmetric" when no harmonic stands above the noise at all;
//  - the largest height outside the contact (over the surface nodes with current radius > a_c,
//    where the piecewise-linear maximum is attained) and its radius and azimuth;
//  - the azimuths of the local maxima of h on the circle r_c that stand above the circle's mean by
//    more than the noise level; maxima closer than 180 / max_fold deg (half the period of the
//    highest harmonic analysed, 15 deg) are one peak, placed at the highest of them or at the
//    mean azimuth of equally high ones;
//  - the height on the indent axis h(0, 0) (after unloading: minus the residual depth).
#pragma once

#include <array>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace indentsim::analysis::pileup
{
  struct SurfaceNode
  {
    double X = 0, Y = 0;              // reference position [um]
    double u_x = 0, u_y = 0, u_z = 0; // displacement [um]

    double x() const { return X + u_x; } // current position [um]
    double y() const { return Y + u_y; }
  };

  // One top-surface face; its corners in cyclic order (around the perimeter, either sense).
  using SurfaceQuad = std::array<SurfaceNode, 4>;

  // The quarter model (X >= 0, Y >= 0) mirrored into all four quadrants through the symmetry
  // planes x = 0 and y = 0: (X, Y, u_x, u_y, u_z) -> (+-X, +-Y, +-u_x, +-u_y, u_z).
  std::vector<SurfaceQuad> mirror_quarter(const std::vector<SurfaceQuad> &quarter);

  // Smallest edge length of the faces in the reference configuration [um].
  double smallest_edge(const std::vector<SurfaceQuad> &surface);

  // Linear interpolation of h = u_z on the triangulated surface in current coordinates.
  class SurfaceInterpolator
  {
  public:
    explicit SurfaceInterpolator(const std::vector<SurfaceQuad> &surface);

    // Height h at the current position (x, y) [um], std::nullopt where no triangle covers it.
    std::optional<double> height(double x, double y) const;

  private:
    struct Triangle
    {
      std::array<double, 3> x, y, h;
    };
    std::vector<Triangle> triangles_;
    // Uniform bins over the bounding box of the current surface; each holds the triangles whose
    // bounding box overlaps it.
    double                                 x_min_ = 0, y_min_ = 0, bin_size_ = 1;
    unsigned int                           n_bins_x_ = 0, n_bins_y_ = 0;
    std::vector<std::vector<unsigned int>> bins_;
  };

  // Heights on the regular grid x_i = -R + i s, y_j = -R + j s (i, j = 0 ... n - 1).
  struct HeightGrid
  {
    double                             half_width = 0; // R [um]
    double                             spacing = 0;    // s [um]
    unsigned int                       n = 0;          // points per side
    std::vector<std::optional<double>> height;         // [um], index i + n j (x fastest)

    double coordinate(const unsigned int i) const { return -half_width + i * spacing; }
  };
  HeightGrid resample_on_grid(const SurfaceInterpolator &surface, double half_width,
                              double spacing);

  struct ProfilePoint
  {
    double                azimuth_deg = 0;
    double                r = 0;  // [um]
    std::optional<double> height; // [um]
  };
  // h(r) at r = 0, dr, 2 dr, ... <= r_max along the azimuth theta (degrees from the x axis).
  std::vector<ProfilePoint> radial_profile(const SurfaceInterpolator &surface, double azimuth_deg,
                                           double r_max, double dr);

  // What besides the square mesh can make the pile-up non-axisymmetric. The defaults assume
  // both (nothing is attributed to the mesh alone).
  struct SymmetrySources
  {
    bool anisotropic_material = true;      // crystal; false for J2 and neo-Hookean
    bool non_axisymmetric_indenter = true; // pyramids; false for cones, spheres, flat punches,
                                           // profile tables
  };

  struct AzimuthalSpectrum
  {
    double              radius = 0;        // [um]
    std::vector<double> samples;           // h(theta_j), theta_j = 360 j / M deg [um]
    std::vector<double> amplitudes;        // A_0 ... A_max_fold [um] (see the file comment)
    unsigned int        dominant_fold = 0; // 0: no harmonic k >= 2 above the noise level
    unsigned int        symmetry_fold = 0; // the fold beyond the square mesh's imprint
    std::string         fold_source = "axisymmetric"; // see the file comment
    double              noise_level = 0;              // max(1e-3 |A_0|, 1e-6) [um]
    std::vector<double> peak_azimuths_deg; // local maxima above mean + noise level, merged
  };
  // The spectrum on the circle of radius `radius`; std::nullopt if a sample is not covered.
  std::optional<AzimuthalSpectrum> azimuthal_spectrum(const SurfaceInterpolator &surface,
                                                      double radius, unsigned int n_azimuths = 360,
                                                      unsigned int           max_fold = 12,
                                                      const SymmetrySources &sources = {});
  // The fold and peak analysis of given equally spaced samples (used by azimuthal_spectrum).
  AzimuthalSpectrum spectrum_of_samples(const std::vector<double> &samples, unsigned int max_fold,
                                        const SymmetrySources &sources = {});

  // One line for the console: the fold, its source and, for an imprint, the harmonic that is
  // the mesh's (e.g. "axisymmetric: no harmonic beyond the square mesh's imprint above the noise
  // level 0.0004 um (A_4 = 0.153 um is the imprint)").
  std::string describe_fold(const AzimuthalSpectrum &spectrum);

  struct PileUpParameters
  {
    double              depth = 0;          // indenter depth of this stage [um]
    double              contact_radius = 0; // a_c at maximum depth [um]
    double              radius_factor = 3;  // R = radius_factor * a_c unless half_width > 0
    double              half_width = 0;     // R [um]; 0: automatic
    double              grid_spacing = 0;   // [um]; 0: min(h_min / 2, R / 50)
    unsigned int        n_azimuths = 360;   // M
    unsigned int        max_fold = 12;
    SymmetrySources     sources; // what besides the mesh can break axial symmetry
    std::vector<double> profile_azimuths_deg = {0,   15,  30,  45,  60,  75,  90,  105,
                                                120, 135, 150, 165, 180, 195, 210, 225,
                                                240, 255, 270, 285, 300, 315, 330, 345};
  };

  struct PileUpResult
  {
    std::string           stage;               // "max_depth" | "unloaded"
    double                depth = 0;           // [um]
    double                contact_radius = 0;  // [um]
    double                analysis_radius = 0; // r_c [um]; 0 if no circle was fully covered
    std::vector<double>   mean_height_by_radius_r, mean_height_by_radius_h; // the r_c search [um]
    AzimuthalSpectrum     spectrum;                                         // on r_c
    double                max_pileup = 0;                                   // [um]
    double                max_pileup_radius = 0;                            // [um]
    double                max_pileup_azimuth_deg = 0;
    std::optional<double> axis_height; // h at r = 0 (minus the impression depth) [um]
    HeightGrid            grid;
    std::vector<ProfilePoint> profiles;
  };

  // The whole analysis of one stage. `surface` is the full surface (mirror a quarter first).
  PileUpResult analyse(const std::vector<SurfaceQuad> &surface, const std::string &stage,
                       const PileUpParameters &parameters);

  // pileup.json: {"units", the fields of `top_level`, "<stage>": {the fields of that stage}...}
  // with the fields stage, depth_um, contact_radius_um, analysis_radius_um, dominant_fold,
  // symmetry_fold, fold_source, noise_level_um, fourier_amplitudes_um [A_0 ... A_max_fold], max_pileup_um,
  // max_pileup_radius_um, max_pileup_azimuth_deg, axis_height_um (null if not covered),
  // peak_azimuths_deg, grid_half_width_um, grid_spacing_um, n_azimuths.
  void write_json(std::ostream &out, const std::vector<PileUpResult> &stages,
                  const PileUpResult &top_level);
  // x_um,y_um,height_um, one row per grid point, empty height where not covered.
  void write_grid_csv(std::ostream &out, const HeightGrid &grid);
  // stage,azimuth_deg,r_um,height_um.
  void write_profiles_csv(std::ostream &out, const std::vector<PileUpResult> &stages);
} // namespace indentsim::analysis::pileup
