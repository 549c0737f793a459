// Tabulated axisymmetric indenter: reading, PCHIP interpolation, exact projection. Units: um.
#include "indenter/ProfileTable.h"

#include "indenter/MinkowskiRounding.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <system_error>

namespace indentsim::indenter
{
  namespace
  {
    // One data row and where it came from, for messages.
    struct Row
    {
      double      first = 0., second = 0.;
      std::string where; // "file:line" or "source (row i)"
    };

    [[noreturn]] void fail(const std::string &where, const std::string &message)
    {
      throw ProfileTableError(where + ": " + message);
    }

    std::string format_number(const double value)
    {
      std::array<char, 64> buffer{};
      const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
      return std::string(buffer.data(), result.ptr);
    }

    std::string trim(const std::string &text)
    {
      const auto first = text.find_first_not_of(" \t");
      if (first == std::string::npos)
        return "";
      const auto last = text.find_last_not_of(" \t");
      return text.substr(first, last - first + 1);
    }

    std::vector<std::string> split_fields(const std::string &line)
    {
      std::vector<std::string> fields;
      std::size_t              start = 0;
      while (true)
        {
          const std::size_t comma = line.find(',', start);
          fields.push_back(trim(line.substr(start, comma - start)));
          if (comma == std::string::npos)
            break;
          start = comma + 1;
        }
      return fields;
    }

    const std::string allowed_headers =
        "allowed: 'r_um,z_um' (the profile: height z above the apex at the distance r from the "
        "axis) or 'depth_um,area_um2' (the area function A(h))";

    // The rules of ProfileTable.h, stated in the columns the user wrote.
    void validate_rows(const std::vector<Row> &rows, const ProfileTable::Kind kind,
                       const std::string &source)
    {
      const bool        area = (kind == ProfileTable::Kind::area_function);
      const std::string first_name = area ? "depth_um" : "r_um";
      const std::string second_name = area ? "area_um2" : "z_um";
      if (rows.size() < 2)
        fail(source, std::to_string(rows.size()) + " data row" + (rows.size() == 1 ? "" : "s") +
                         "; at least 2 rows are needed (the apex 0,0 and at least one more)");
      if (rows[0].first != 0. || rows[0].second != 0.)
        fail(rows[0].where, "the first row must be the apex 0,0 (" + first_name + " = 0, " +
                                second_name + " = 0), got " + format_number(rows[0].first) + "," +
                                format_number(rows[0].second));
      for (std::size_t i = 1; i < rows.size(); ++i)
        {
          const Row &row = rows[i], &previous = rows[i - 1];
          if (!(row.first > previous.first))
            fail(row.where,
                 first_name + " = " + format_number(row.first) +
                     " does not increase (previous row: " + format_number(previous.first) + "); " +
                     first_name + " must be strictly increasing");
          if (area && !(row.second > previous.second))
            fail(row.where, second_name + " = " + format_number(row.second) +
                                " does not increase (previous row: " +
                                format_number(previous.second) + "); " + second_name +
                                " must be strictly increasing (a constant area would be a "
                                "vertical wall, which is not a profile z(r))");
          if (!area && row.second < previous.second)
            fail(row.where, second_name + " = " + format_number(row.second) +
                                " is below the previous row's " + format_number(previous.second) +
                                "; " + second_name +
                                " must be non-decreasing (z(r) of an indenter "
                                "that opens upwards)");
        }
      if (!area && !(rows.back().second > rows[rows.size() - 2].second))
        fail(rows.back().where,
             "the last two rows have the same z_um = " + format_number(rows.back().second) +
                 "; the table must end rising, because the profile continues beyond its last row "
                 "with the last slope (a flat continuation would be an infinite flat plane)");
    }

    // Descartes' rule of signs for the Bernstein form: the number of sign changes of the
    // coefficients bounds the number of roots in the interval, with the same parity.
    int sign_changes(const std::array<double, 6> &b)
    {
      int    changes = 0;
      double last = 0.;
      for (const double c : b)
        if (c != 0.)
          {
            if (last != 0. && (c > 0.) != (last > 0.))
              ++changes;
            last = c;
          }
      return changes;
    }

    // de Casteljau subdivision at the midpoint.
    void split(const std::array<double, 6> &b, std::array<double, 6> &left,
               std::array<double, 6> &right)
    {
      std::array<double, 6> work = b;
      for (int level = 0; level < 6; ++level)
        {
          left[level] = work[0];
          right[5 - level] = work[5 - level];
          for (int i = 0; i < 5 - level; ++i)
            work[i] = 0.5 * (work[i] + work[i + 1]);
        }
    }
  } // namespace

  ProfileTable ProfileTable::read(const std::string &path)
  {
    std::error_code error;
    if (!std::filesystem::exists(path, error))
      throw ProfileTableError(path + ": the profile table does not exist (" + allowed_headers +
                              ")");
    if (std::filesystem::is_directory(path, error))
      throw ProfileTableError(path + ": is a directory, expected a CSV profile table");
    std::ifstream input(path);
    if (!input)
      throw ProfileTableError(path + ": the profile table cannot be opened for reading");

    ProfileTable     table;
    bool             have_header = false;
    std::vector<Row> rows;
    std::string      line;
    int              line_number = 0;
    while (std::getline(input, line))
      {
        ++line_number;
        if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
          line.erase(0, 3); // UTF-8 byte-order mark
        if (!line.empty() && line.back() == '\r')
          line.pop_back();
        const std::string text = trim(line);
        if (text.empty() || text[0] == '#')
          continue;
        const std::string              where = path + ":" + std::to_string(line_number);
        const std::vector<std::string> fields = split_fields(text);
        if (!have_header)
          {
            if (fields.size() == 2 && fields[0] == "r_um" && fields[1] == "z_um")
              table.table_kind = Kind::profile;
            else if (fields.size() == 2 && fields[0] == "depth_um" && fields[1] == "area_um2")
              table.table_kind = Kind::area_function;
            else
              fail(where, "header '" + text + "' is not recognised; " + allowed_headers);
            have_header = true;
            continue;
          }
        const std::string columns =
            table.table_kind == Kind::profile ? "r_um,z_um" : "depth_um,area_um2";
        if (fields.size() != 2)
          fail(where, "'" + text + "': expected 2 comma-separated numbers (" + columns + "), got " +
                          std::to_string(fields.size()) + " fields");
        Row row;
        row.where = where;
        for (int column = 0; column < 2; ++column)
          {
            const std::string &field = fields[column];
            const std::size_t  start = (!field.empty() && field[0] == '+') ? 1 : 0;
            double             value = 0.;
            const auto         result =
                std::from_chars(field.data() + start, field.data() + field.size(), value);
            if (field.empty() || result.ec != std::errc() ||
                result.ptr != field.data() + field.size() || !std::isfinite(value))
              fail(where, "'" + field + "' is not a number; each row holds two finite numbers (" +
                              columns + "), e.g. '0.5,0.02'");
            (column == 0 ? row.first : row.second) = value;
          }
        rows.push_back(row);
      }
    if (!have_header)
      fail(path, "the file is empty (no header line); " + allowed_headers);
    validate_rows(rows, table.table_kind, path);

    table.source_name = path;
    for (const Row &row : rows)
      if (table.table_kind == Kind::profile)
        {
          table.r.push_back(row.first);
          table.z.push_back(row.second);
        }
      else
        {
          // The profile with the same projected area at every depth: r(h) = sqrt(A(h) / pi).
          table.r.push_back(std::sqrt(row.second / std::numbers::pi));
          table.z.push_back(row.first);
        }
    table.build();
    return table;
  }

  ProfileTable::ProfileTable(std::vector<double> radii, std::vector<double> heights,
                             const std::string &source)
    : table_kind(Kind::profile)
    , source_name(source)
    , r(std::move(radii))
    , z(std::move(heights))
  {
    if (r.size() != z.size())
      fail(source, "radii and heights differ in length");
    std::vector<Row> rows(r.size());
    for (std::size_t i = 0; i < r.size(); ++i)
      {
        if (!std::isfinite(r[i]) || !std::isfinite(z[i]))
          fail(source + " (row " + std::to_string(i + 1) + ")", "non-finite value");
        rows[i] = {r[i], z[i], source + " (row " + std::to_string(i + 1) + ")"};
      }
    validate_rows(rows, Kind::profile, source);
    build();
  }

  void ProfileTable::build()
  {
    const std::size_t   n = r.size(); // >= 2
    std::vector<double> width(n - 1), secant(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k)
      {
        width[k] = r[k + 1] - r[k];
        secant[k] = (z[k + 1] - z[k]) / width[k];
      }
    dz_dr.assign(n, 0.);
    if (n == 2)
      dz_dr[0] = secant[0];
    else
      {
        // Interior: weighted harmonic mean of the neighbouring secants, 0 at a local extremum
        // or next to a flat piece (keeps every piece monotone).
        for (std::size_t k = 1; k + 1 < n; ++k)
          if (secant[k - 1] * secant[k] > 0.)
            {
              const double w1 = 2. * width[k] + width[k - 1];
              const double w2 = width[k] + 2. * width[k - 1];
              dz_dr[k] = (w1 + w2) / (w1 / secant[k - 1] + w2 / secant[k]);
            }
        // r = 0: the one-sided three-point estimate, limited to keep the first piece monotone.
        double start =
            ((2. * width[0] + width[1]) * secant[0] - width[0] * secant[1]) / (width[0] + width[1]);
        if (start * secant[0] <= 0.)
          start = 0.;
        else if (secant[0] * secant[1] <= 0. && std::abs(start) > 3. * std::abs(secant[0]))
          start = 3. * secant[0];
        dz_dr[0] = start;
      }
    // The last row: the last secant, which the straight continuation beyond the table keeps.
    dz_dr[n - 1] = secant[n - 2];

    // z range of each piece from its Bezier control points (convex hull property).
    box_low.resize(n - 1);
    box_high.resize(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k)
      {
        const double c1 = z[k] + dz_dr[k] * width[k] / 3.;
        const double c2 = z[k + 1] - dz_dr[k + 1] * width[k] / 3.;
        box_low[k] = std::min({z[k], c1, c2, z[k + 1]});
        box_high[k] = std::max({z[k], c1, c2, z[k + 1]});
      }
  }

  std::size_t ProfileTable::piece_of(const double radius) const
  {
    const auto after = std::upper_bound(r.begin(), r.end(), radius);
    if (after == r.end())
      return r.size() - 1;
    return after == r.begin() ? 0 : static_cast<std::size_t>(after - r.begin()) - 1;
  }

  namespace
  {
    // Power-form coefficients in t = (r - r_k) / (r_{k+1} - r_k) of the Hermite cubic on a piece.
    std::array<double, 4> hermite_coefficients(const double z0, const double z1, const double d0,
                                               const double d1, const double width)
    {
      const double rise = z1 - z0;
      return {{z0, width * d0, 3. * rise - 2. * width * d0 - width * d1,
               -2. * rise + width * d0 + width * d1}};
    }

    double horner(const std::array<double, 4> &c, const double t)
    {
      return ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
    }

    double horner_derivative(const std::array<double, 4> &c, const double t)
    {
      return (3. * c[3] * t + 2. * c[2]) * t + c[1];
    }
  } // namespace

  double ProfileTable::profile_at_radius(const double radius) const
  {
    const std::size_t last = r.size() - 1;
    if (radius >= r[last])
      return z[last] + dz_dr[last] * (radius - r[last]);
    const std::size_t k = piece_of(std::max(radius, 0.));
    const double      width = r[k + 1] - r[k];
    const auto        c = hermite_coefficients(z[k], z[k + 1], dz_dr[k], dz_dr[k + 1], width);
    return horner(c, (std::max(radius, 0.) - r[k]) / width);
  }

  double ProfileTable::slope_at_radius(const double radius) const
  {
    const std::size_t last = r.size() - 1;
    if (radius >= r[last])
      return dz_dr[last];
    const std::size_t k = piece_of(std::max(radius, 0.));
    const double      width = r[k + 1] - r[k];
    const auto        c = hermite_coefficients(z[k], z[k + 1], dz_dr[k], dz_dr[k + 1], width);
    return horner_derivative(c, (std::max(radius, 0.) - r[k]) / width) / width;
  }

  double ProfileTable::profile(const double x, const double y) const
  {
    return profile_at_radius(std::hypot(x, y));
  }

  double ProfileTable::radius_at_height(const double h) const
  {
    if (!(h > 0.))
      return 0.;
    const std::size_t last = r.size() - 1;
    if (h > z[last])
      return r[last] + (h - z[last]) / dz_dr[last];
    // The first row at or above h closes the (monotone, rising) piece that reaches h.
    const std::size_t i =
        static_cast<std::size_t>(std::lower_bound(z.begin(), z.end(), h) - z.begin());
    const std::size_t k = i - 1; // z[k] < h <= z[k + 1]
    const double      width = r[k + 1] - r[k];
    const auto        c = hermite_coefficients(z[k], z[k + 1], dz_dr[k], dz_dr[k + 1], width);
    double            lo = 0., hi = 1.;
    double            t = (h - z[k]) / (z[k + 1] - z[k]);
    for (unsigned int iteration = 0; iteration < 200 && hi - lo > 1e-16; ++iteration)
      {
        const double value = horner(c, t) - h;
        if (value == 0.)
          break;
        (value < 0. ? lo : hi) = t;
        const double slope = horner_derivative(c, t);
        double       next = slope > 0. ? t - value / slope : 0.5 * (lo + hi);
        if (!(next > lo && next < hi))
          next = 0.5 * (lo + hi);
        const bool done = std::abs(next - t) <= 1e-16;
        t = next;
        if (done)
          break;
      }
    return r[k] + width * t;
  }

  double ProfileTable::projected_area(const double h) const
  {
    const double radius = radius_at_height(h);
    return std::numbers::pi * radius * radius;
  }

  void ProfileTable::Closest::consider(const double radius, const double height)
  {
    const double distance = std::hypot(radius - rho, height - zeta);
    if (distance < best)
      {
        best = distance;
        foot_r = radius;
        foot_z = height;
      }
  }

  void ProfileTable::closest_on_piece(const std::size_t k, Closest &closest) const
  {
    const double rho = closest.rho, zeta = closest.zeta;
    // Skip the piece if its bounding box is farther than the best point so far.
    const double below = std::max({0., r[k] - rho, rho - r[k + 1]});
    const double beside = std::max({0., box_low[k] - zeta, zeta - box_high[k]});
    if (!(std::hypot(below, beside) < closest.best))
      return;
    // The stationary points of (r - rho)^2 + (f(r) - zeta)^2 are the roots of
    // g = (r - rho) + (f - zeta) f'. In t on [0, 1], G = width g is the quintic
    //   width (r_k - rho) + width^2 t + (F(t) - zeta) F'(t),  F(t) = f(r_k + width t).
    const double          width = r[k + 1] - r[k];
    const auto            F = hermite_coefficients(z[k], z[k + 1], dz_dr[k], dz_dr[k + 1], width);
    std::array<double, 4> P = F;
    P[0] -= zeta;
    const std::array<double, 3> Q = {{F[1], 2. * F[2], 3. * F[3]}};
    std::array<double, 6>       power{};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j)
        power[i + j] += P[i] * Q[j];
    power[0] += width * (r[k] - rho);
    power[1] += width * width;

    // Bernstein coefficients b_i = sum_{j <= i} C(i, j) / C(5, j) p_j.
    static constexpr double binomial[6][6] = {{1, 0, 0, 0, 0, 0}, {1, 1, 0, 0, 0, 0},
                                              {1, 2, 1, 0, 0, 0}, {1, 3, 3, 1, 0, 0},
                                              {1, 4, 6, 4, 1, 0}, {1, 5, 10, 10, 5, 1}};
    std::array<double, 6>   bernstein{};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j <= i; ++j)
        bernstein[i] += binomial[i][j] / binomial[5][j] * power[j];

    const auto G = [&](const double t) {
      double value = 0.;
      for (int i = 5; i >= 0; --i)
        value = value * t + power[i];
      return value;
    };
    const auto dG = [&](const double t) {
      double value = 0.;
      for (int i = 5; i >= 1; --i)
        value = value * t + i * power[i];
      return value;
    };
    const auto foot_at = [&](const double t) { closest.consider(r[k] + width * t, horner(F, t)); };
    // The single root in [t0, t1] (G(t0) and G(t1) of opposite signs): Newton safeguarded
    // by bisection.
    const auto refine = [&](double lo, double hi) {
      const bool rising = G(lo) < 0.;
      double     t = 0.5 * (lo + hi);
      for (unsigned int iteration = 0; iteration < 200; ++iteration)
        {
          const double value = G(t);
          if (value == 0.)
            break;
          ((value < 0.) == rising ? lo : hi) = t;
          const double slope = dG(t);
          double       next = slope != 0. ? t - value / slope : 0.5 * (lo + hi);
          if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
          const bool done = std::abs(next - t) <= 2. * std::numeric_limits<double>::epsilon() ||
                            hi - lo <= 2. * std::numeric_limits<double>::epsilon();
          t = next;
          if (done)
            break;
        }
      return t;
    };
    // Root isolation by midpoint subdivision of the Bernstein form.
    const auto isolate = [&](const auto &self, const std::array<double, 6> &b, const double t0,
                             const double t1, const int level) -> void {
      if (b[0] == 0.)
        foot_at(t0);
      const int changes = sign_changes(b);
      if (changes == 0)
        return;
      if (changes == 1 && b[0] != 0. && b[5] != 0.)
        {
          foot_at(refine(t0, t1));
          return;
        }
      if (level >= 52) // interval at round-off width: a multiple root
        {
          foot_at(0.5 * (t0 + t1));
          return;
        }
      std::array<double, 6> left{}, right{};
      split(b, left, right);
      const double middle = 0.5 * (t0 + t1);
      self(self, left, t0, middle, level + 1);
      self(self, right, middle, t1, level + 1);
    };
    isolate(isolate, bernstein, 0., 1., 0);
  }

  SurfaceProjection ProfileTable::project(const Point<3> &x, const double depth) const
  {
    const double zeta = x[2] + depth; // height above the apex
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(zeta))
      return failed_projection();
    // The closest point lies in the point's meridian half-plane (x-z plane on the axis).
    const double rho = std::hypot(x[0], x[1]);
    const double cos_phi = rho > 0. ? x[0] / rho : 1.;
    const double sin_phi = rho > 0. ? x[1] / rho : 0.;

    Closest closest{rho, zeta};
    // The rows (the apex among them) bound the distance from above.
    const std::size_t n = r.size(), last = n - 1;
    for (std::size_t i = 0; i < n; ++i)
      closest.consider(r[i], z[i]);
    // The straight continuation z = z_N + s (r - r_N), r >= r_N.
    {
      const double s = dz_dr[last];
      const double along = ((rho - r[last]) + s * (zeta - z[last])) / (1. + s * s);
      if (along > 0.)
        closest.consider(r[last] + along, z[last] + s * along);
    }
    // Each cubic piece.
    for (std::size_t k = 0; k < last; ++k)
      closest_on_piece(k, closest);

    const double      best = closest.best, foot_r = closest.foot_r;
    SurfaceProjection result;
    result.closest_point = Point<3>(foot_r * cos_phi, foot_r * sin_phi, closest.foot_z - depth);
    const bool inside = zeta > profile_at_radius(rho);
    if (foot_r == 0. && dz_dr[0] > 0. && best > 0.)
      {
        // A conical apex has no tangent plane: the normal is the direction to the point.
        const Tensor<1, 3> offset({x[0], x[1], zeta});
        result.normal = offset / robust_norm(offset);
        result.gap = best;
      }
    else
      {
        // Meridian normal (f', -1) / sqrt(1 + f'^2), from the indenter into the specimen.
        const double s = slope_at_radius(foot_r);
        const double norm = std::sqrt(1. + s * s);
        result.normal = Tensor<1, 3>({s * cos_phi / norm, s * sin_phi / norm, -1. / norm});
        result.gap = inside ? -best : best;
      }
    return result;
  }
} // namespace indentsim::indenter
