// default_case: the Case that holds the schema's defaults (the one place a default is written is
// its schema row, src/case/schema.cpp).
#include "particula/case/case.hpp"
#include "particula/case/schema.hpp"

namespace particula {
namespace {

/// Every row of a plain key (not a member of an array of tables) that has a default applies it
/// through its binding, in the table's order.
Case make_default_case() {
  Case c;
  for (const KeySpec& spec : case_schema())
    if (!spec.in_array() && spec.need == Need::Default) spec.bind.set(c, 0, spec.default_at(0));
  return c;
}

}  // namespace

Case default_case() {
  static const Case defaults = make_default_case();
  return defaults;
}

}  // namespace particula
