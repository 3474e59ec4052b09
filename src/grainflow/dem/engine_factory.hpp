// The soft-sphere engine for a case: one DemEngine<Law> per registered contact law, without and
// with rolling resistance, in a variant, so the time loop is compiled once per law and the force
// loop inlines the law.
#pragma once

#include <variant>

#include "grainflow/config/case_config.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/dem/derived_quantities.hpp"

namespace grainflow::dem {

template <class List>
struct EngineVariantOf;
template <ContactLaw... Laws>
struct EngineVariantOf<ContactLawList<Laws...>> {
  using type = std::variant<DemEngine<Laws, false>..., DemEngine<Laws, true>...>;
};
using DemEngineVariant = EngineVariantOf<RegisteredContactLaws>::type;

// Builds the engine for the case's contact model from an initial state; with `domain`, as one of
// several MPI ranks (`state` is then the whole initial state, the same on every rank).
DemEngineVariant make_engine(const CaseConfig& c, DemState state, int threads, const EngineDomain* domain = nullptr);

}  // namespace grainflow::dem
