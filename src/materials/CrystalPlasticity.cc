#include "materials/CrystalPlasticity.h"
#include "materials/crystal/CrystalPlasticityModel.templates.h"

namespace indentsim::materials
{
  template class CrystalPlasticityModel<CubicElasticity, RegularizedSchmidFlow,
                                        ExtendedVoceHardening>;
} // namespace indentsim::materials
