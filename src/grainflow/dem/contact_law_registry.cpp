#include "grainflow/dem/contact_law_registry.hpp"

#include <array>

namespace grainflow::dem {
namespace {

template <ContactLaw Law>
ContactSchema schema_of() {
  return {Law::name, Law::keys, Law::wall_keys, &Law::read, &Law::read_wall};
}

template <ContactLaw... Laws>
std::array<ContactSchema, sizeof...(Laws)> schemas_of(ContactLawList<Laws...>) {
  return {schema_of<Laws>()...};
}

}  // namespace

ContactSchemas contact_schemas() {
  static const auto schemas = schemas_of(RegisteredContactLaws{});
  return schemas;
}

std::string contact_law_names() { return schema_names(contact_schemas()); }

}  // namespace grainflow::dem
