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

std::size_t symmetry_label(const math::SymmetrySpec& spec, std::span<char> out) {
  char text[kSymmetryLabelSize] = {};
  std::size_t n = 0;
  const auto put = [&](char c) {
    if (n + 1 < sizeof text) text[n++] = c;
  };
  switch (spec.kind) {
    case math::SymmetryKind::none:
      for (const char c : {'n', 'o', 'n', 'e'}) put(c);
      break;
    case math::SymmetryKind::mirrors:
      for (std::uint8_t axis = 0; axis < 3; ++axis) {
        if ((spec.mirrors & (1u << axis)) != 0) put(static_cast<char>('x' + axis));
      }
      break;
    case math::SymmetryKind::rotation:
    case math::SymmetryKind::rotation_mirror:
      for (const char c : {'r', 'o', 't'}) put(c);
      if (spec.order >= 10) put(static_cast<char>('0' + spec.order / 10));
      put(static_cast<char>('0' + spec.order % 10));
      if (spec.kind == math::SymmetryKind::rotation_mirror) put('m');
      put(' ');
      put(static_cast<char>('x' + (spec.axis % 3)));
      break;
  }
  if (out.empty()) return 0;
  const std::size_t written = n < out.size() ? n : out.size() - 1;
  for (std::size_t i = 0; i < written; ++i) out[i] = text[i];
  out[written] = '\0';
  return written;
}

}  // namespace twister::session
