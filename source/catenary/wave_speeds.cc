#include <pantocat/catenary/wave_speeds.h>

#include <iomanip>

namespace pantocat
{
namespace
{
WireWaveSpeed wire_wave_speed(const WireParameters& wire, const double v)
{
  WireWaveSpeed w;
  w.wave_speed = wire.wave_speed();
  w.speed_ratio = v / w.wave_speed;
  w.doppler_factor = (w.wave_speed - v) / (w.wave_speed + v);
  return w;
}

void print_wire(std::ostream& out, const char* name, const WireWaveSpeed& w)
{
  out << "    " << name << ": c = " << w.wave_speed << " m/s (" << 3.6 * w.wave_speed
      << " km/h), v/c = " << w.speed_ratio
      << ", Doppler factor (c - v)/(c + v) = " << w.doppler_factor << '\n';
}
} // namespace

CatenaryWaveSpeeds wave_speeds(const CatenaryParameters& catenary, const double v)
{
  return {wire_wave_speed(catenary.carrier, v), wire_wave_speed(catenary.contact_wire, v),
          v};
}

void print_wave_speeds(std::ostream& out, const CatenaryWaveSpeeds& w, const bool brief)
{
  const auto flags = out.flags();
  const auto precision = out.precision();
  if (brief)
    out << std::setprecision(4)
        << "  wave speeds: contact wire c = " << w.contact_wire.wave_speed
        << " m/s (v/c = " << w.contact_wire.speed_ratio
        << "), messenger c = " << w.carrier.wave_speed
        << " m/s (v/c = " << w.carrier.speed_ratio << ")\n";
  else
  {
    out << std::setprecision(4) << "  wave speeds sqrt(T / rho A) at v = " << w.speed
        << " m/s (" << 3.6 * w.speed << " km/h):\n";
    print_wire(out, "contact wire", w.contact_wire);
    print_wire(out, "carrier", w.carrier);
  }
  if (w.exceeds_design_limit())
    out << "  warning: v = " << w.contact_wire.speed_ratio
        << " c of the contact wire exceeds the design limit 0.7 c of EN 50119 ("
        << CatenaryWaveSpeeds::design_limit * 3.6 * w.contact_wire.wave_speed
        << " km/h): wave reflections and the Doppler effect grow the contact-force "
           "variation\n";
  out.flags(flags);
  out.precision(precision);
}
} // namespace pantocat
