#include "materials/CrystalPlasticity.h"
#include "materials/crystal/CrystalPlasticityModel.templates.h"

namespace indentsim::materials
{
  template class CrystalPlasticityModel<LatticeElasticity, RegularizedSchmidFlow,
                                        FamilyVoceHardening>;
} // namespace indentsim::materials
