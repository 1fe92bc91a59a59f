#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/space/fdm_catenary.h>
#include <pantocat/space/fem_catenary.h>

namespace pantocat
{
const char* block_name(const Wire wire)
{
  return wire == Wire::carrier ? "carrier" : "contact wire";
}

CatenaryDiscretisation::CatenaryDiscretisation(
    const CatenaryParameters& catenary, const DiscretisationParameters& discretisation)
    : catenary(catenary), discretisation(discretisation),
      delta(discretisation.load_half_width),
      dx(catenary.length() / discretisation.n_intervals),
      stitch(catenary, dx, discretisation.method == SpaceMethod::fdm),
      supports(catenary.support_positions()), chord_kinks(catenary.support_chord_kinks())
{
}

const WireParameters& CatenaryDiscretisation::wire_parameters(const Wire wire) const
{
  return wire == Wire::carrier ? catenary.carrier : catenary.contact_wire;
}

void CatenaryDiscretisation::assemble(const Wire wire, BlockOperator& op) const
{
  const WireParameters& p = wire_parameters(wire);
  // The paper's carrier is a string, Eq. (2): E I_c = 0 (and no C1 element).
  const double bending = has_bending_element(wire) ? p.bending_stiffness : 0.;
  initialize_operator(wire, bending > 0., op);
  add_terms(wire,
            {p.mass_per_length, p.damping, p.tension, bending,
             p.mass_per_length * catenary.gravity},
            op);
}

double CatenaryDiscretisation::displacement(const Wire wire,
                                            const dealii::Vector<double>& q,
                                            const double x) const
{
  const double offset = wire == Wire::carrier ? catenary.support_height : 0.;
  return offset + point_row(wire, x).dot(q);
}

std::string CatenaryDiscretisation::wire_block_name(const Wire wire) const
{
  return catenary.name.empty() ? std::string(block_name(wire))
                               : catenary.name + " " + block_name(wire);
}

std::string CatenaryDiscretisation::stitch_block_name() const
{
  return catenary.name.empty() ? std::string(StitchWireSpace::block_name)
                               : catenary.name + " " + StitchWireSpace::block_name;
}

double CatenaryDiscretisation::reference_height(const double x,
                                                const unsigned int k) const
{
  if (catenary.support_heights.empty())
    return 0.;
  const std::vector<double>& s = supports;
  const std::vector<double>& kinks = chord_kinks;
  const bool point = discretisation.load_shape == LoadShape::point;
  if (k == 2)
  {
    // h'' = sum of kink_i delta(y - s_i): the load shape at the supports.
    double sum = 0.;
    for (unsigned int i = 0; i < s.size() && !point; ++i)
      sum += kinks[i] * delta.value(s[i] - x);
    return sum;
  }
  if (point)
    return catenary.support_chord(x, k);
  // h' is 0 before the first anchor and jumps by kink_i at s_i: weighted by
  // the load shape, each jump counts with the load's share beyond s_i. h is
  // the integral of that from the level before the first anchor.
  double value = k == 0 ? catenary.support_heights.front() : 0.;
  for (unsigned int i = 0; i < s.size(); ++i)
    value += kinks[i] * (k == 0 ? delta.first_moment_beyond(s[i] - x)
                                : 1. - delta.integral_up_to(s[i] - x));
  return value;
}

std::vector<double> CatenaryDiscretisation::grid_points() const
{
  std::vector<double> x(n_intervals() + 1);
  for (unsigned int i = 0; i <= n_intervals(); ++i)
    x[i] = catenary.length() * i / n_intervals();
  return x;
}

std::unique_ptr<CatenaryDiscretisation>
create_catenary_discretisation(const CatenaryParameters& catenary,
                               const DiscretisationParameters& discretisation)
{
  if (discretisation.method == SpaceMethod::fem)
    return std::make_unique<FemCatenary>(catenary, discretisation);
  return std::make_unique<FdmCatenary>(catenary, discretisation);
}
SparseRow wire_point_row(const CatenaryDiscretisation& d,
                         const SemiDiscreteSystem& system, const Wire wire,
                         const double x)
{
  if (!system.has_block(d.wire_block_name(wire)))
    return {};
  SparseRow row = d.point_row(wire, x);
  row.shift(system.block(d.wire_block_name(wire)).first);
  return row;
}

SparseRow stitch_wire_point_row(const CatenaryDiscretisation& d,
                                const SemiDiscreteSystem& system, const unsigned int i,
                                const double x)
{
  if (!system.has_block(d.stitch_block_name()))
    return {};
  SparseRow row = d.stitch_wires().point_row(i, x);
  row.shift(system.block(d.stitch_block_name()).first);
  return row;
}

SparseRow dropper_upper_row(const CatenaryDiscretisation& d,
                            const SemiDiscreteSystem& system, const unsigned int j)
{
  const CatenaryParameters& c = d.catenary_parameters();
  const double x = c.dropper_positions[j];
  const unsigned int s = c.stitch_wire_of(j);
  return s == no_stitch_wire ? wire_point_row(d, system, Wire::carrier, x)
                             : stitch_wire_point_row(d, system, s, x);
}
} // namespace pantocat
