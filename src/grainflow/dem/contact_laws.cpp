#include "grainflow/dem/contact_laws.hpp"

namespace grainflow::dem {

DemEngineVariant make_engine(const CaseConfig& c, DemState state, int threads, const EngineDomain* domain) {
  const DerivedQuantities d = derive(c);
  const int sort_every = c.run.sort_every;
  if (c.contact.model == "walton_braun") {
    const double ratk = d.tangential_stiffness / d.k1;
    const auto pair = WaltonBraun::make(c.contact.k1, c.contact.restitution, ratk, c.contact.friction);
    std::vector<WaltonBraun::Params> walls;
    for (const auto& wall : state.walls) walls.push_back(WaltonBraun::make(c.contact.k1, wall.restitution, ratk, wall.friction));
    return DemEngineVariant(std::in_place_type<DemEngine<WaltonBraun>>, std::move(state), pair, walls, threads, sort_every, domain);
  }
  const LinearDashpot::Params pair{c.contact.kn, c.contact.kt, c.contact.gamma_n, c.contact.gamma_t, c.contact.friction};
  std::vector<LinearDashpot::Params> walls;
  for (const auto& wall : state.walls) {
    LinearDashpot::Params p = pair;
    p.gamma_n = wall.gamma_n;
    p.friction = wall.friction;
    walls.push_back(p);
  }
  return DemEngineVariant(std::in_place_type<DemEngine<LinearDashpot>>, std::move(state), pair, walls, threads, sort_every, domain);
}

}  // namespace grainflow::dem
