// A depth-graded material (see LayeredMaterial.h).
#include "materials/LayeredMaterial.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace indentsim::materials
{
  LayeredMaterial::LayeredMaterial(std::vector<std::unique_ptr<MaterialModel>> layers,
                                   std::vector<double>                         thicknesses,
                                   std::unique_ptr<MaterialModel>              substrate)
    : models_(std::move(layers))
  {
    if (thicknesses.size() != models_.size() || !substrate)
      throw std::invalid_argument("LayeredMaterial: one thickness per layer and a substrate");
    models_.push_back(std::move(substrate));
    double depth = 0;
    for (const double thickness : thicknesses)
      {
        if (!(thickness >= 0) || !std::isfinite(thickness))
          throw std::invalid_argument("LayeredMaterial: a layer thickness must be >= 0 um");
        depth += thickness;
        lower_boundaries_.push_back(depth);
      }
    for (const auto &model : models_)
      if (model->n_state_variables() != models_.back()->n_state_variables())
        throw std::invalid_argument("LayeredMaterial: every layer needs the substrate's kind of "
                                    "material (the same state variables)");
  }

  unsigned int LayeredMaterial::layer_at_depth(const double depth) const
  {
    return static_cast<unsigned int>(
        std::upper_bound(lower_boundaries_.begin(), lower_boundaries_.end(), depth) -
        lower_boundaries_.begin());
  }

  unsigned int LayeredMaterial::n_state_variables() const
  {
    return 1 + models_.back()->n_state_variables();
  }

  void LayeredMaterial::initial_state(std::span<double> state) const
  {
    state[0] = static_cast<double>(models_.size() - 1);
    models_.back()->initial_state(state.subspan(1));
  }

  void LayeredMaterial::oriented_initial_state(std::span<double>   state,
                                               const Tensor<2, 3> &orientation) const
  {
    state[0] = static_cast<double>(models_.size() - 1);
    models_.back()->oriented_initial_state(state.subspan(1), orientation);
  }

  void LayeredMaterial::initial_state_at_depth(std::span<double>   state,
                                               const Tensor<2, 3> &orientation,
                                               const double        depth) const
  {
    const unsigned int layer = layer_at_depth(depth);
    state[0] = static_cast<double>(layer);
    models_[layer]->oriented_initial_state(state.subspan(1), orientation);
  }

  unsigned int LayeredMaterial::layer_of(std::span<const double> state) const
  {
    // A whole number written by the initial state; clamped so that a corrupted state cannot
    // index out of range.
    const double stored = std::round(state[0]);
    return stored >= 0 && stored < static_cast<double>(models_.size())
               ? static_cast<unsigned int>(stored)
               : static_cast<unsigned int>(models_.size() - 1);
  }

  const MaterialModel &LayeredMaterial::model_of(std::span<const double> state) const
  {
    return *models_[layer_of(state)];
  }

  UpdateStatus LayeredMaterial::update(const Tensor<2, 3> &F, std::span<const double> state_old,
                                       MaterialPointResponse &response, std::span<double> state_new,
                                       const bool compute_tangent) const
  {
    state_new[0] = state_old[0];
    return model_of(state_old).update(F, state_old.subspan(1), response, state_new.subspan(1),
                                      compute_tangent);
  }

  double LayeredMaterial::equivalent_plastic_strain(std::span<const double> state) const
  {
    return model_of(state).equivalent_plastic_strain(state.subspan(1));
  }

  double LayeredMaterial::reference_modulus() const
  {
    return models_.back()->reference_modulus();
  }

  bool LayeredMaterial::symmetric_tangent() const
  {
    return std::all_of(models_.begin(), models_.end(),
                       [](const auto &model) { return model->symmetric_tangent(); });
  }

  double LayeredMaterial::relative_plastic_cost() const
  {
    return models_.back()->relative_plastic_cost();
  }
} // namespace indentsim::materials
