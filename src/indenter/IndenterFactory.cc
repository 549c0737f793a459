// The one place that maps indenter.shape to an IndenterSurface implementation.
#include "indenter/IndenterFactory.h"
#include "indenter/Cone.h"
#include "indenter/FlatPunch.h"
#include "indenter/ProfileTable.h"
#include "indenter/Pyramid.h"
#include "indenter/RoundedCone.h"
#include "indenter/Sphere.h"

#include <stdexcept>

namespace indentsim::indenter
{
  std::unique_ptr<IndenterSurface> create_indenter(const io::IndenterParameters &parameters)
  {
    using Shape = io::IndenterShape;
    if (parameters.shape.known())
      switch (parameters.shape.value())
        {
        case Shape::rounded_cone:
          return std::make_unique<RoundedCone>(parameters.a, parameters.delta);
        case Shape::sphere:
          return std::make_unique<Sphere>(parameters.radius);
        case Shape::cone:
          return std::make_unique<Cone>(parameters.half_angle_deg, parameters.tip_radius);
        case Shape::vickers:
          return std::make_unique<Pyramid>(
              Pyramid::vickers(parameters.tip_radius, parameters.rotation_deg));
        case Shape::berkovich:
          return std::make_unique<Pyramid>(
              Pyramid::berkovich(parameters.tip_radius, parameters.rotation_deg));
        case Shape::flat_punch:
          return std::make_unique<FlatPunch>(parameters.radius, parameters.edge_radius);
        case Shape::profile_table:
          return std::make_unique<ProfileTable>(ProfileTable::read(parameters.file));
        }
    throw std::invalid_argument("indenter.shape = '" + to_string(parameters.shape) +
                                "': unknown indenter shape; allowed: rounded_cone | sphere | "
                                "cone | vickers | berkovich | flat_punch | profile_table");
  }
} // namespace indentsim::indenter
