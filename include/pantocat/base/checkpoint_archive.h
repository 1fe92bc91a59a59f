#pragma once

/**
 * @file
 * The archives of a checkpoint: Boost's binary archives, declared
 * here only, so that the headers of integrators and observers need not pull
 * in Boost.Serialization. A .cc file that writes or reads one includes
 * pantocat/base/serialization.h.
 */
namespace boost::archive
{
class binary_oarchive;
class binary_iarchive;
} // namespace boost::archive

namespace pantocat
{
using CheckpointOut = boost::archive::binary_oarchive;
using CheckpointIn = boost::archive::binary_iarchive;
} // namespace pantocat
