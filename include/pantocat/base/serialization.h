#pragma once

#include <pantocat/base/checkpoint_archive.h>
#include <pantocat/time/dynamic_state.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

namespace pantocat
{
/// A state of (35) in a checkpoint: every bit of q, v, a, lambda and the active set.
template <class Archive>
void serialize(Archive& archive, DynamicState& s, const unsigned int /*version*/)
{
  archive& s.t;
  archive& s.q;
  archive& s.v;
  archive& s.a;
  archive& s.lambda;
  archive& s.active;
}
} // namespace pantocat
