#include "grainflow/dem/engine_factory.hpp"

#include <vector>

namespace grainflow::dem {

DemEngineVariant make_engine(const CaseConfig& c, DemState state, int threads, const EngineDomain* domain) {
  const SpeciesConfig& reference = c.species[derive(c).reference_species];
  return visit_contact_law(c.contact.model, [&]<ContactLaw Law>() {
    const typename Law::Params pair = Law::pair_params(c.contact, reference);
    std::vector<typename Law::Params> walls;
    for (const auto& wall : state.walls) walls.push_back(Law::wall_params(pair, c.walls[wall.face].contact, wall.friction));
    return DemEngineVariant(std::in_place_type<DemEngine<Law>>, std::move(state), pair, std::move(walls), threads,
                            c.run.sort_every, domain);
  });
}

}  // namespace grainflow::dem
