#include "grainflow/dem/engine_factory.hpp"

#include <vector>

#include "grainflow/dem/rolling_resistance.hpp"

namespace grainflow::dem {
namespace {

// A wall's material keys: its face's [walls.FACE] or its [[geometry]] table's.
const WallConfig& material(const CaseConfig& c, const DemWall& wall) {
  return wall.face >= 0 ? c.walls[wall.face] : c.geometry[wall.geometry].material;
}

}  // namespace

DemEngineVariant make_engine(const CaseConfig& c, DemState state, int threads, const EngineDomain* domain) {
  const DerivedQuantities d = derive(c);
  const SpeciesConfig& reference = c.species[d.reference_species];
  return visit_contact_law(c.contact.model, [&]<ContactLaw Law>() {
    const typename Law::Params pair = Law::pair_params(c.contact, reference);
    std::vector<typename Law::Params> walls;
    for (const auto& wall : state.walls)
      walls.push_back(Law::wall_params(pair, material(c, wall).contact, wall.friction));
    if (rolling_model_named(c.contact.rolling_model) == RollingModel::none)
      return DemEngineVariant(std::in_place_type<DemEngine<Law, false>>, std::move(state), pair, std::move(walls),
                              threads, c.run.sort_every, domain);
    RollingSetup rolling;
    rolling.pair = rolling_params(c.contact, c.contact.rolling_friction, d.normal_stiffness);
    for (const auto& wall : state.walls) {
      const double mu_r = material(c, wall).rolling_friction;
      rolling.walls.push_back(
          rolling_params(c.contact, mu_r >= 0.0 ? mu_r : c.contact.rolling_friction, d.normal_stiffness));
    }
    return DemEngineVariant(std::in_place_type<DemEngine<Law, true>>, std::move(state), pair, std::move(walls), threads,
                            c.run.sort_every, domain, std::move(rolling));
  });
}

}  // namespace grainflow::dem
