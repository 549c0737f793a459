// A depth-graded material (material.layers): one model per layer from the surface down and the
// substrate below them, all of one kind (the case validator sees to it), so that their states
// have one layout. Each material point belongs to the layer of its depth below the undeformed
// surface for the whole run: the layer's number is the first variable of its state, set once by
// initial_state_at_depth, and every call is passed on to that layer's model with the rest of
// the state. Units: um, GPa.
#pragma once

#include "materials/MaterialModel.h"

#include <memory>
#include <vector>

namespace indentsim::materials
{
  class LayeredMaterial : public MaterialModel
  {
  public:
    // `layers` from the surface down with their thicknesses [um] (>= 0; a layer of thickness 0
    // holds no point), then `substrate`. Throws std::invalid_argument if the models' states
    // differ in size or the counts do not match.
    LayeredMaterial(std::vector<std::unique_ptr<MaterialModel>> layers,
                    std::vector<double> thicknesses, std::unique_ptr<MaterialModel> substrate);

    // The layer holding the depth d [um] below the surface: the first whose lower boundary lies
    // deeper than d (a point on a boundary belongs to the deeper layer); the number of layers
    // for the substrate.
    unsigned int layer_at_depth(double depth) const;

    unsigned int n_state_variables() const override;
    // The substrate's state (a point whose depth is not known).
    void         initial_state(std::span<double> state) const override;
    void         oriented_initial_state(std::span<double>   state,
                                        const Tensor<2, 3> &orientation) const override;
    void         initial_state_at_depth(std::span<double> state, const Tensor<2, 3> &orientation,
                                        double depth) const override;
    UpdateStatus update(const Tensor<2, 3> &F, std::span<const double> state_old,
                        MaterialPointResponse &response, std::span<double> state_new,
                        bool compute_tangent = true) const override;
    double       equivalent_plastic_strain(std::span<const double> state) const override;
    // The substrate's: penalties and tolerances do not change with a layer.
    double reference_modulus() const override;
    bool   symmetric_tangent() const override;
    double relative_plastic_cost() const override;

    // The layer number stored in a state.
    unsigned int layer_of(std::span<const double> state) const;

  private:
    std::vector<std::unique_ptr<MaterialModel>> models_;           // layers, then the substrate
    std::vector<double>                         lower_boundaries_; // depth of each layer's bottom
    const MaterialModel                        &model_of(std::span<const double> state) const;
  };
} // namespace indentsim::materials
