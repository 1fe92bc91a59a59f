#pragma once

#include <pantocat/base/serialization.h>
#include <pantocat/time/dynamic_state.h>

namespace pantocat
{
/// A state of (35) in a checkpoint: every bit of q, v, a, lambda, the active set
/// and the impulses.
template <class Archive>
void serialize(Archive& archive, DynamicState& s, const unsigned int /*version*/)
{
  archive& s.t;
  archive& s.q;
  archive& s.v;
  archive& s.a;
  archive& s.lambda;
  archive& s.active;
  archive& s.impulse;
}
} // namespace pantocat
