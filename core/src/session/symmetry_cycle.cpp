// SymmetryCycle: the sculptor's cycle of symmetry groups, and their labels.
#include "twister/session/symmetry_cycle.hpp"

namespace twister::session {

SymmetryCycle SymmetryCycle::resolved(const math::SymmetrySpec& configured) const {
  if (count > 0) return *this;
  SymmetryCycle c;
  c.push(math::SymmetrySpec{}).ignore();
  if (configured != math::SymmetrySpec{}) c.push(configured).ignore();
  return c;
}

Status SymmetryCycle::push(const math::SymmetrySpec& spec) {
  if (count >= groups.size() || !math::valid_symmetry(spec)) return StatusCode::invalid_argument;
  groups[count++] = spec;
  return ok_status();
}

Result<math::SymmetrySpec> SymmetryCycle::next(const math::SymmetrySpec& current) const {
  if (count < 2) return StatusCode::failed_precondition;
  for (std::size_t i = 0; i < count; ++i) {
    if (groups[i] == current) return groups[(i + 1) % count];
  }
  return groups[0];
}

}  // namespace twister::session
