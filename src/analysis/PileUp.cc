// Pile-up analysis of the indented top surface; see PileUp.h. Units: um, deg.
#include "analysis/PileUp.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

namespace indentsim::analysis::pileup
{
  namespace
  {
    constexpr double degree = std::numbers::pi / 180.;

    // Harmonics below this fraction of the mean height on the circle (or below 1e-6 um) are
    // noise: round-off and the interpolation error of a fine mesh.
    constexpr double relative_noise = 1e-3, absolute_noise = 1e-6;
    // A harmonic that a square mesh cannot produce counts as the material's fold when it reaches
    // this fraction of the largest harmonic k >= 2 (see spectrum_of_samples).
    constexpr double mesh_free_fraction = 0.1;

    // Azimuth of (x, y) in [0, 360) deg.
    double azimuth_deg(const double x, const double y)
    {
      const double angle = std::atan2(y, x) / degree;
      return angle < 0 ? angle + 360. : angle;
    }

    // The heights on a circle of radius r around the indent axis at theta_j = 2 pi j / M, or
    // std::nullopt if one of them is not covered by the surface.
    std::optional<std::vector<double>> circle_samples(const SurfaceInterpolator &surface,
                                                      const double radius, const unsigned int n)
    {
      std::vector<double> samples(n);
      for (unsigned int j = 0; j < n; ++j)
        {
          const double theta = 2. * std::numbers::pi * j / n;
          const auto   h = surface.height(radius * std::cos(theta), radius * std::sin(theta));
          if (!h)
            return std::nullopt;
          samples[j] = *h;
        }
      return samples;
    }

    // Merges local maxima closer than `separation` degrees (cyclically) into one peak: the
    // spectrum is analysed up to k = max_fold, so features closer than half the period of its
    // highest harmonic are not separate peaks of the pattern (on a piecewise-linear surface a
    // crest crossing a mesh line shows as two maxima a few degrees apart). A merged peak lies
    // at the highest member, or at the mean azimuth of the members within `tie` of it (a
    // symmetric pair around a mirror plane merges onto the plane). Sorted azimuths in [0, 360).
    template <typename Peak>
    std::vector<double> merge_close_peaks(std::vector<Peak> maxima, const double separation,
                                          const double tie)
    {
      std::vector<double> merged;
      if (maxima.empty())
        return merged;
      std::sort(maxima.begin(), maxima.end(),
                [](const Peak &a, const Peak &b) { return a.azimuth < b.azimuth; });
      // Start after the largest gap, so that no cluster straddles the starting point.
      const std::size_t n = maxima.size();
      std::size_t       start = 0;
      double            largest_gap = -1;
      for (std::size_t i = 0; i < n; ++i)
        {
          const double gap = i == 0 ? maxima[0].azimuth + 360. - maxima[n - 1].azimuth
                                    : maxima[i].azimuth - maxima[i - 1].azimuth;
          if (gap > largest_gap)
            {
              largest_gap = gap;
              start = i;
            }
        }
      std::vector<Peak> cluster;
      const auto        close_cluster = [&]() {
        double highest = cluster.front().height;
        for (const Peak &p : cluster)
          highest = std::max(highest, p.height);
        double sum = 0;
        int    count = 0;
        for (const Peak &p : cluster)
          if (p.height >= highest - tie)
            {
              sum += p.azimuth;
              ++count;
            }
        merged.push_back(std::fmod(sum / count, 360.));
        cluster.clear();
      };
      double previous = 0;
      for (std::size_t m = 0; m < n; ++m)
        {
          Peak peak = maxima[(start + m) % n];
          // Unwrap the azimuths after the start so that they increase monotonically.
          if (m > 0 && peak.azimuth < previous)
            peak.azimuth += 360.;
          if (m > 0 && peak.azimuth - previous >= separation)
            close_cluster();
          cluster.push_back(peak);
          previous = peak.azimuth;
        }
      close_cluster();
      std::sort(merged.begin(), merged.end());
      return merged;
    }

    void write_number(std::ostream &out, const double value)
    {
      // JSON has no NaN or infinity; the analysis never produces them (asserted).
      assert(std::isfinite(value));
      out << std::setprecision(10) << (value == 0 ? 0. : value);
    }

    void write_array(std::ostream &out, const std::vector<double> &values)
    {
      out << '[';
      for (std::size_t i = 0; i < values.size(); ++i)
        {
          if (i > 0)
            out << ", ";
          write_number(out, values[i]);
        }
      out << ']';
    }

    // The fields of one stage, each on its own line with `indent`.
    void write_stage_fields(std::ostream &out, const PileUpResult &r, const std::string &indent)
    {
      const auto field = [&](const char *name) -> std::ostream & {
        return out << indent << '"' << name << "\": ";
      };
      const auto number = [&](const char *name, const double value) {
        field(name);
        write_number(out, value);
        out << ",\n";
      };
      const auto array = [&](const char *name, const std::vector<double> &values) {
        field(name);
        write_array(out, values);
        out << ",\n";
      };
      field("stage") << '"' << r.stage << "\",\n";
      number("depth_um", r.depth);
      number("contact_radius_um", r.contact_radius);
      number("analysis_radius_um", r.analysis_radius);
      field("dominant_fold") << r.spectrum.dominant_fold << ",\n";
      field("symmetry_fold") << r.spectrum.symmetry_fold << ",\n";
      field("fold_source") << '"' << r.spectrum.fold_source << "\",\n";
      number("noise_level_um", r.spectrum.noise_level);
      array("fourier_amplitudes_um", r.spectrum.amplitudes);
      number("max_pileup_um", r.max_pileup);
      number("max_pileup_radius_um", r.max_pileup_radius);
      number("max_pileup_azimuth_deg", r.max_pileup_azimuth_deg);
      field("axis_height_um");
      if (r.axis_height)
        write_number(out, *r.axis_height);
      else
        out << "null";
      out << ",\n";
      array("peak_azimuths_deg", r.spectrum.peak_azimuths_deg);
      number("grid_half_width_um", r.grid.half_width);
      number("grid_spacing_um", r.grid.spacing);
      field("n_azimuths") << r.spectrum.samples.size();
    }

    void write_optional(std::ostream &out, const std::optional<double> &value)
    {
      if (value)
        write_number(out, *value);
    }
  } // namespace

  std::vector<SurfaceQuad> mirror_quarter(const std::vector<SurfaceQuad> &quarter)
  {
    std::vector<SurfaceQuad> full;
    full.reserve(4 * quarter.size());
    // The original first: ties in a maximum are then reported in the modelled quadrant.
    for (const double sx : {1., -1.})
      for (const double sy : {1., -1.})
        for (const SurfaceQuad &quad : quarter)
          {
            SurfaceQuad mirrored = quad;
            for (SurfaceNode &node : mirrored)
              {
                node.X *= sx;
                node.u_x *= sx;
                node.Y *= sy;
                node.u_y *= sy;
              }
            full.push_back(mirrored);
          }
    return full;
  }

  double smallest_edge(const std::vector<SurfaceQuad> &surface)
  {
    double smallest = std::numeric_limits<double>::infinity();
    for (const SurfaceQuad &quad : surface)
      for (unsigned int v = 0; v < 4; ++v)
        {
          const SurfaceNode &a = quad[v], &b = quad[(v + 1) % 4];
          const double       length = std::hypot(b.X - a.X, b.Y - a.Y);
          if (length > 0)
            smallest = std::min(smallest, length);
        }
    return smallest;
  }

  SurfaceInterpolator::SurfaceInterpolator(const std::vector<SurfaceQuad> &surface)
  {
    // Each quad becomes four triangles around its vertex average, which carries the mean of
    // the corner heights. That point lies on the finite-element surface (a bilinear field takes
    // the corner mean at the element centre, and the centre maps to the vertex average), a
    // linear field is still reproduced exactly, and no diagonal is preferred: a split into two
    // triangles picks one diagonal where both are equally long (every undistorted square) and
    // so adds a spurious 2-fold component to the spectrum of a full model.
    triangles_.reserve(4 * surface.size());
    for (const SurfaceQuad &q : surface)
      {
        double x_c = 0, y_c = 0, h_c = 0;
        for (const SurfaceNode &corner : q)
          {
            x_c += 0.25 * corner.x();
            y_c += 0.25 * corner.y();
            h_c += 0.25 * corner.u_z;
          }
        for (unsigned int v = 0; v < 4; ++v)
          {
            const SurfaceNode &a = q[v], &b = q[(v + 1) % 4];
            triangles_.push_back(
                Triangle{{{a.x(), b.x(), x_c}}, {{a.y(), b.y(), y_c}}, {{a.u_z, b.u_z, h_c}}});
          }
      }
    if (triangles_.empty())
      return;

    double x_max = -std::numeric_limits<double>::infinity(), y_max = x_max;
    x_min_ = y_min_ = std::numeric_limits<double>::infinity();
    for (const Triangle &t : triangles_)
      for (unsigned int v = 0; v < 3; ++v)
        {
          x_min_ = std::min(x_min_, t.x[v]);
          y_min_ = std::min(y_min_, t.y[v]);
          x_max = std::max(x_max, t.x[v]);
          y_max = std::max(y_max, t.y[v]);
        }
    // About as many bins as triangles, at most 512 per side.
    const double width = std::max(x_max - x_min_, y_max - y_min_);
    const double n_per_side = std::clamp(std::ceil(std::sqrt(double(triangles_.size()))), 1., 512.);
    bin_size_ = width > 0 ? width / n_per_side : 1.;
    n_bins_x_ = std::max(1u, unsigned(std::ceil((x_max - x_min_) / bin_size_)) + 1);
    n_bins_y_ = std::max(1u, unsigned(std::ceil((y_max - y_min_) / bin_size_)) + 1);
    bins_.assign(std::size_t(n_bins_x_) * n_bins_y_, {});
    for (unsigned int index = 0; index < triangles_.size(); ++index)
      {
        const Triangle &t = triangles_[index];
        const auto      bin = [&](const double value, const double origin, const unsigned int n) {
          return std::min(n - 1, unsigned(std::max(0., std::floor((value - origin) / bin_size_))));
        };
        const unsigned int i0 = bin(*std::min_element(t.x.begin(), t.x.end()), x_min_, n_bins_x_);
        const unsigned int i1 = bin(*std::max_element(t.x.begin(), t.x.end()), x_min_, n_bins_x_);
        const unsigned int j0 = bin(*std::min_element(t.y.begin(), t.y.end()), y_min_, n_bins_y_);
        const unsigned int j1 = bin(*std::max_element(t.y.begin(), t.y.end()), y_min_, n_bins_y_);
        for (unsigned int j = j0; j <= j1; ++j)
          for (unsigned int i = i0; i <= i1; ++i)
            bins_[i + std::size_t(n_bins_x_) * j].push_back(index);
      }
  }

  std::optional<double> SurfaceInterpolator::height(const double x, const double y) const
  {
    if (bins_.empty())
      return std::nullopt;
    // A point outside the bounding box is looked up in the nearest bin (and found in none of
    // its triangles); the bin index is computed as for the triangles' bounding boxes.
    const double       fi = std::floor((x - x_min_) / bin_size_);
    const double       fj = std::floor((y - y_min_) / bin_size_);
    const unsigned int i = unsigned(std::clamp(fi, 0., double(n_bins_x_ - 1)));
    const unsigned int j = unsigned(std::clamp(fj, 0., double(n_bins_y_ - 1)));
    for (const unsigned int index : bins_[i + std::size_t(n_bins_x_) * j])
      {
        const Triangle &t = triangles_[index];
        // Barycentric coordinates (l0, l1, l2); inside if all >= -eps (eps relative: points on
        // a shared edge belong to either neighbour, whose values agree there).
        const double det =
            (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
        const double scale = std::abs(t.x[1] - t.x[0]) + std::abs(t.y[1] - t.y[0]) +
                             std::abs(t.x[2] - t.x[0]) + std::abs(t.y[2] - t.y[0]);
        if (std::abs(det) <= 1e-14 * scale * scale) // degenerate (e.g. a collapsed corner)
          continue;
        const double l1 =
            ((x - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (y - t.y[0])) / det;
        const double l2 =
            ((t.x[1] - t.x[0]) * (y - t.y[0]) - (x - t.x[0]) * (t.y[1] - t.y[0])) / det;
        const double     l0 = 1. - l1 - l2;
        constexpr double eps = 1e-10;
        if (l0 >= -eps && l1 >= -eps && l2 >= -eps)
          return l0 * t.h[0] + l1 * t.h[1] + l2 * t.h[2];
      }
    return std::nullopt;
  }

  HeightGrid resample_on_grid(const SurfaceInterpolator &surface, const double half_width,
                              const double spacing)
  {
    assert(half_width > 0 && spacing > 0);
    HeightGrid grid;
    grid.half_width = half_width;
    // n points with (n - 1) s = 2 R exactly: the spacing is adjusted down to fit.
    grid.n = unsigned(std::ceil(2. * half_width / spacing - 1e-9)) + 1;
    grid.spacing = 2. * half_width / (grid.n - 1);
    grid.height.resize(std::size_t(grid.n) * grid.n);
    for (unsigned int j = 0; j < grid.n; ++j)
      for (unsigned int i = 0; i < grid.n; ++i)
        grid.height[i + std::size_t(grid.n) * j] =
            surface.height(grid.coordinate(i), grid.coordinate(j));
    return grid;
  }

  std::vector<ProfilePoint> radial_profile(const SurfaceInterpolator &surface, const double azimuth,
                                           const double r_max, const double dr)
  {
    assert(dr > 0);
    std::vector<ProfilePoint> profile;
    const double              c = std::cos(azimuth * degree), s = std::sin(azimuth * degree);
    const unsigned int        n = unsigned(std::floor(r_max / dr + 1e-9));
    for (unsigned int i = 0; i <= n; ++i)
      {
        const double r = i * dr;
        profile.push_back({azimuth, r, surface.height(r * c, r * s)});
      }
    return profile;
  }

  AzimuthalSpectrum spectrum_of_samples(const std::vector<double> &samples,
                                        const unsigned int max_fold, const SymmetrySources &sources)
  {
    AzimuthalSpectrum spectrum;
    spectrum.samples = samples;
    spectrum.amplitudes.assign(max_fold + 1, 0.);
    const unsigned int n = samples.size();
    if (n == 0)
      return spectrum;

    // Discrete Fourier coefficients c_k = (1/M) sum_j h_j exp(-i k theta_j); the mean c_0 is
    // reported as A_0 and taken out of the harmonics (which are insensitive to it anyway).
    double mean = 0;
    for (const double h : samples)
      mean += h / n;
    spectrum.amplitudes[0] = mean;
    for (unsigned int k = 1; k <= max_fold; ++k)
      {
        std::complex<double> c = 0;
        for (unsigned int j = 0; j < n; ++j)
          c += (samples[j] - mean) * std::polar(1., -2. * std::numbers::pi * k * j / n);
        // A_k = 2 |c_k| for k < M/2 (the amplitude of A_k cos(k theta - phi_k)).
        spectrum.amplitudes[k] = (2 * k == n ? 1. : 2.) * std::abs(c) / n;
      }

    // The dominant fold is sought among k >= 2 only: k = 1 (one bump on one side) is not a
    // symmetry of the pile-up but a displacement of its centre from the analysis axis (an
    // off-centre or tilted indent); it vanishes identically for a mirrored quarter model and by
    // symmetry for a centred indent on a cubic crystal in the paper's orientations.
    spectrum.noise_level = std::max(relative_noise * std::abs(mean), absolute_noise);
    double largest = spectrum.noise_level;
    for (unsigned int k = 2; k <= max_fold; ++k)
      if (spectrum.amplitudes[k] > largest)
        {
          largest = spectrum.amplitudes[k];
          spectrum.dominant_fold = k;
        }

    // The fold beyond the mesh imprint. The tensor-product mesh is invariant under the square's
    // symmetry group (rotations by 90 deg, mirrors x = 0 and y = 0): on an isotropic material it
    // can only add harmonics k = 4, 8, 12, ... to the pile-up, and on coarse meshes these are as
    // large as the crystal's own 2-fold (011) or 3-fold (111) pattern. A harmonic that is not a
    // multiple of 4 cannot come from the mesh; if the largest of them is significant (above the
    // noise level and at least `mesh_free_fraction` of the largest harmonic k >= 2), its k is
    // the fold of the material's pattern. Otherwise the pattern is compatible with the square
    // (a 4-fold crystal such as (001), or an isotropic material seen through the mesh) and the
    // dominant fold stands.
    spectrum.symmetry_fold = spectrum.dominant_fold;
    double       largest_off_mesh = 0;
    unsigned int off_mesh_fold = 0;
    for (unsigned int k = 2; k <= max_fold; ++k)
      if (k % 4 != 0 && spectrum.amplitudes[k] > largest_off_mesh)
        {
          largest_off_mesh = spectrum.amplitudes[k];
          off_mesh_fold = k;
        }
    if (spectrum.dominant_fold != 0 && largest_off_mesh > spectrum.noise_level &&
        largest_off_mesh >= mesh_free_fraction * largest)
      spectrum.symmetry_fold = off_mesh_fold;

    // Where the fold comes from. An isotropic material under an axisymmetric indenter has no
    // fold: the square mesh is then the only thing that is not axisymmetric, and it imprints
    // k = 4, 8, 12 only (the reported fold of such a pile-up would be the mesh's). A harmonic
    // beyond the imprint above the noise level is then a numerical asymmetry.
    if (!sources.anisotropic_material && !sources.non_axisymmetric_indenter)
      {
        const bool asymmetric = largest_off_mesh > spectrum.noise_level;
        spectrum.symmetry_fold = asymmetric ? off_mesh_fold : 0;
        spectrum.fold_source = asymmetric ? "numerical" : "axisymmetric";
      }
    else if (spectrum.symmetry_fold == 0)
      spectrum.fold_source = "axisymmetric";
    else if (spectrum.symmetry_fold % 4 == 0)
      spectrum.fold_source = "mesh_imprint_possible";
    else
      spectrum.fold_source = !sources.non_axisymmetric_indenter ? "crystal"
                             : !sources.anisotropic_material    ? "indenter"
                                                                : "crystal_or_indenter";

    // Local maxima of the cyclic sample sequence (a plateau counts once, at its centre) that
    // stand above the mean by more than the noise level.
    struct Peak
    {
      double azimuth, height;
    };
    std::vector<Peak> maxima;
    for (unsigned int j = 0; j < n; ++j)
      {
        const double h = samples[j];
        if (!(h > samples[(j + n - 1) % n]))
          continue;
        unsigned int end = j; // last sample of a plateau starting at j
        while (end < j + n - 1 && samples[(end + 1) % n] == h)
          ++end;
        if (samples[(end + 1) % n] < h && h - mean > spectrum.noise_level)
          maxima.push_back({0.5 * (j + end) * 360. / n, h});
      }
    spectrum.peak_azimuths_deg = merge_close_peaks(maxima, 180. / max_fold, spectrum.noise_level);
    return spectrum;
  }

  std::optional<AzimuthalSpectrum> azimuthal_spectrum(const SurfaceInterpolator &surface,
                                                      const double               radius,
                                                      const unsigned int         n_azimuths,
                                                      const unsigned int         max_fold,
                                                      const SymmetrySources     &sources)
  {
    const auto samples = circle_samples(surface, radius, n_azimuths);
    if (!samples)
      return std::nullopt;
    AzimuthalSpectrum spectrum = spectrum_of_samples(*samples, max_fold, sources);
    spectrum.radius = radius;
    return spectrum;
  }

  PileUpResult analyse(const std::vector<SurfaceQuad> &surface, const std::string &stage,
                       const PileUpParameters &parameters)
  {
    PileUpResult result;
    result.stage = stage;
    result.depth = parameters.depth;
    result.contact_radius = parameters.contact_radius;
    result.spectrum.amplitudes.assign(parameters.max_fold + 1, 0.);
    if (surface.empty())
      return result;

    const SurfaceInterpolator interpolator(surface);
    const double              a_c = parameters.contact_radius;
    const double              h_min = smallest_edge(surface);
    // Without contact (a_c = 0) the region is scaled by the smallest element instead.
    const double half_width = parameters.half_width > 0 ? parameters.half_width
                              : a_c > 0                 ? parameters.radius_factor * a_c
                                                        : parameters.radius_factor * h_min;
    // Half the smallest element resolves the piecewise-linear field; at least 101 points per
    // side so that the map is readable on coarse meshes.
    const double spacing = parameters.grid_spacing > 0 ? parameters.grid_spacing
                                                       : std::min(0.5 * h_min, half_width / 50.);
    result.grid = resample_on_grid(interpolator, half_width, spacing);
    result.axis_height = interpolator.height(0, 0);
    for (const double azimuth : parameters.profile_azimuths_deg)
      {
        const auto profile = radial_profile(interpolator, azimuth, half_width, result.grid.spacing);
        result.profiles.insert(result.profiles.end(), profile.begin(), profile.end());
      }

    // The analysis radius: the crest of the pile-up ring, i.e. the largest azimuthal mean height
    // over the fully covered circles a_c < r <= R, searched in steps of half the grid spacing.
    const double dr = 0.5 * result.grid.spacing;
    double       best_mean = -std::numeric_limits<double>::infinity();
    for (unsigned int i = 1;; ++i)
      {
        const double r = a_c + i * dr;
        if (r > half_width * (1 + 1e-12))
          break;
        const auto samples = circle_samples(interpolator, r, parameters.n_azimuths);
        if (!samples)
          continue;
        double mean = 0;
        for (const double h : *samples)
          mean += h / samples->size();
        result.mean_height_by_radius_r.push_back(r);
        result.mean_height_by_radius_h.push_back(mean);
        if (mean > best_mean)
          {
            best_mean = mean;
            result.analysis_radius = r;
          }
      }
    if (result.analysis_radius > 0)
      result.spectrum =
          *azimuthal_spectrum(interpolator, result.analysis_radius, parameters.n_azimuths,
                              parameters.max_fold, parameters.sources);

    // The largest height outside the contact: a piecewise-linear surface takes its maximum at a
    // node, so the nodes with current radius > a_c are searched.
    bool found = false;
    for (const SurfaceQuad &quad : surface)
      for (const SurfaceNode &node : quad)
        {
          const double r = std::hypot(node.x(), node.y());
          if (r > a_c && (!found || node.u_z > result.max_pileup))
            {
              found = true;
              result.max_pileup = node.u_z;
              result.max_pileup_radius = r;
              result.max_pileup_azimuth_deg = azimuth_deg(node.x(), node.y());
            }
        }
    return result;
  }

  std::string describe_fold(const AzimuthalSpectrum &spectrum)
  {
    std::ostringstream out;
    out << std::setprecision(3);
    const unsigned int largest = spectrum.dominant_fold;
    const auto         harmonic = [&](const unsigned int k) -> std::ostream         &{
      return out << "A_" << k << " = " << spectrum.amplitudes[k] << " um";
    };
    if (spectrum.fold_source == "axisymmetric")
      {
        out << "axisymmetric (no fold): no harmonic ";
        if (largest != 0 && largest % 4 == 0)
          {
            out << "beyond the square mesh's 4/8/12-fold imprint stands above the noise level "
                << spectrum.noise_level << " um; the largest, ";
            harmonic(largest) << ", is the mesh's imprint";
          }
        else
          out << "stands above the noise level " << spectrum.noise_level << " um";
        return out.str();
      }
    out << spectrum.symmetry_fold << "-fold (";
    if (spectrum.fold_source == "crystal")
      out << "the crystal's: the square mesh imprints multiples of 4 only";
    else if (spectrum.fold_source == "indenter")
      out << "the indenter's: the square mesh imprints multiples of 4 only";
    else if (spectrum.fold_source == "crystal_or_indenter")
      out << "the crystal's or the indenter's: the square mesh imprints multiples of 4 only";
    else if (spectrum.fold_source == "mesh_imprint_possible")
      out << "a multiple of 4: the crystal's or indenter's fold and the square mesh's imprint "
             "cannot be told apart on one mesh";
    else
      out << "numerical asymmetry: an isotropic material under an axisymmetric indenter has no "
             "fold";
    out << "; ";
    harmonic(spectrum.symmetry_fold) << ", largest harmonic " << largest << ")";
    return out.str();
  }

  void write_json(std::ostream &out, const std::vector<PileUpResult> &stages,
                  const PileUpResult &top_level)
  {
    out << "{\n"
        << "  \"units\": \"um, deg\",\n";
    write_stage_fields(out, top_level, "  ");
    for (const PileUpResult &stage : stages)
      {
        out << ",\n  \"" << stage.stage << "\": {\n";
        write_stage_fields(out, stage, "    ");
        out << "\n  }";
      }
    out << "\n}\n";
  }

  void write_grid_csv(std::ostream &out, const HeightGrid &grid)
  {
    out << "x_um,y_um,height_um\n";
    for (unsigned int j = 0; j < grid.n; ++j)
      for (unsigned int i = 0; i < grid.n; ++i)
        {
          write_number(out, grid.coordinate(i));
          out << ',';
          write_number(out, grid.coordinate(j));
          out << ',';
          write_optional(out, grid.height[i + std::size_t(grid.n) * j]);
          out << '\n';
        }
  }

  void write_profiles_csv(std::ostream &out, const std::vector<PileUpResult> &stages)
  {
    out << "stage,azimuth_deg,r_um,height_um\n";
    for (const PileUpResult &stage : stages)
      for (const ProfilePoint &point : stage.profiles)
        {
          out << stage.stage << ',';
          write_number(out, point.azimuth_deg);
          out << ',';
          write_number(out, point.r);
          out << ',';
          write_optional(out, point.height);
          out << '\n';
        }
  }
} // namespace indentsim::analysis::pileup
