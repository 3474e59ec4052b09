// The contact laws a case may choose (contact.model). Adding a law: its own file (a type that
// satisfies ContactLaw, contact_law.hpp, whose .cpp instantiates DemEngine for it) and one entry in
// RegisteredContactLaws; the case loader, writer, `check`, `theory`, `calibrate`, the engine
// variant and the typed law tests follow.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "grainflow/config/contact_schema.hpp"
#include "grainflow/dem/contact_law.hpp"
#include "grainflow/dem/hertz_mindlin.hpp"
#include "grainflow/dem/jkr.hpp"
#include "grainflow/dem/linear_dashpot.hpp"
#include "grainflow/dem/walton_braun.hpp"

namespace grainflow::dem {

template <ContactLaw... Laws>
struct ContactLawList {};

// The first is the default of contact.model.
using RegisteredContactLaws = ContactLawList<WaltonBraun, LinearDashpot, HertzMindlin, Jkr>;

// The registered names, comma-separated, for messages.
std::string contact_law_names();

// The case loader's view of every registered law.
ContactSchemas contact_schemas();

namespace registry_detail {
template <class F, ContactLaw First, ContactLaw... Rest>
decltype(auto) visit_one(std::string_view name, F&& f) {
  if (name == First::name) return f.template operator()<First>();
  if constexpr (sizeof...(Rest) > 0) {
    return visit_one<F, Rest...>(name, std::forward<F>(f));
  } else {
    throw std::invalid_argument("unknown contact law '" + std::string(name) + "' (registered: " + contact_law_names() +
                                ")");
  }
}
template <class F, ContactLaw... Laws>
decltype(auto) visit(std::string_view name, F&& f, ContactLawList<Laws...>) {
  return visit_one<F, Laws...>(name, std::forward<F>(f));
}
}  // namespace registry_detail

// Calls f.template operator()<Law>() for the law called `name` and returns its result. The name
// has been checked by the case loader; an unknown one here is a programming error.
template <class F>
decltype(auto) visit_contact_law(std::string_view name, F&& f) {
  return registry_detail::visit(name, std::forward<F>(f), RegisteredContactLaws{});
}

// Calls f.template operator()<Law>() for every registered law, in order.
template <class F>
void for_each_contact_law(F&& f) {
  [&]<ContactLaw... Laws>(ContactLawList<Laws...>) { (f.template operator()<Laws>(), ...); }
  (RegisteredContactLaws{});
}

}  // namespace grainflow::dem
