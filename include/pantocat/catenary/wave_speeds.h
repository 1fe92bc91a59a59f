#pragma once

#include <pantocat/catenary/catenary_parameters.h>

#include <ostream>

namespace pantocat
{
/**
 * The transverse wave speed c = sqrt(T / rho A) of one wire and what a
 * pantograph at speed v makes of it: the ratio v / c and the Doppler factor
 * alpha = (c - v) / (c + v), the ratio of the frequencies of the waves
 * reflected ahead of and behind a moving load (alpha -> 0 as v -> c, where a
 * string's response to a moving load grows without bound).
 */
struct WireWaveSpeed
{
  double wave_speed = 0.;     ///< c [m/s]
  double speed_ratio = 0.;    ///< v / c
  double doppler_factor = 0.; ///< alpha = (c - v) / (c + v)
};

/// Wave speeds of both wires for a pantograph at speed @p v [m/s].
struct CatenaryWaveSpeeds
{
  WireWaveSpeed carrier, contact_wire;
  double speed = 0.; ///< v [m/s]

  /// EN 50119 design rule: v <= 0.7 c of the contact wire.
  static constexpr double design_limit = 0.7;
  bool exceeds_design_limit() const { return contact_wire.speed_ratio > design_limit; }
};

CatenaryWaveSpeeds wave_speeds(const CatenaryParameters& catenary, double v);

/// A line per wire (@p brief: both in one line): c, v/c and alpha; a warning
/// when v > 0.7 c.
void print_wave_speeds(std::ostream& out, const CatenaryWaveSpeeds& w,
                       bool brief = false);
} // namespace pantocat
