// The one place that maps indenter.shape to an IndenterSurface implementation.
#include <indenter/Cone.h>
#include <indenter/FlatPunch.h>
#include <indenter/IndenterFactory.h>
#include <indenter/ProfileTable.h>
#include <indenter/Pyramid.h>
#include <indenter/RoundedCone.h>
#include <indenter/Sphere.h>

#include <stdexcept>

namespace indentsim::indenter
{
  std::unique_ptr<IndenterSurface> create_indenter(const io::IndenterParameters &parameters)
  {
    const std::string &shape = parameters.shape;
    if (shape == "rounded_cone")
      return std::make_unique<RoundedCone>(parameters.a, parameters.delta);
    if (shape == "sphere")
      return std::make_unique<Sphere>(parameters.radius);
    if (shape == "cone")
      return std::make_unique<Cone>(parameters.half_angle_deg, parameters.tip_radius);
    if (shape == "vickers")
      return std::make_unique<Pyramid>(
        Pyramid::vickers(parameters.tip_radius, parameters.rotation_deg));
    if (shape == "berkovich")
      return std::make_unique<Pyramid>(
        Pyramid::berkovich(parameters.tip_radius, parameters.rotation_deg));
    if (shape == "flat_punch")
      return std::make_unique<FlatPunch>(parameters.radius, parameters.edge_radius);
    if (shape == "profile_table")
      return std::make_unique<ProfileTable>(ProfileTable::read(parameters.file));
    throw std::invalid_argument("indenter.shape = '" + shape +
                                "': unknown indenter shape; allowed: rounded_cone | sphere | "
                                "cone | vickers | berkovich | flat_punch | profile_table");
  }
} // namespace indentsim::indenter
