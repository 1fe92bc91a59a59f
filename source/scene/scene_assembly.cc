#include <pantocat/base/number_format.h>
#include <pantocat/pantograph/pantograph_registry.h>
#include <pantocat/scene/scene_assembly.h>
#include <pantocat/space/catenary_discretisation.h>

namespace pantocat
{
std::vector<ScenePantograph> make_scene_pantographs(const SceneParameters& scene)
{
  std::vector<ScenePantograph> list;
  const std::size_t n = scene.pantographs.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const PantographCase& data = scene.pantographs[k];
    ScenePantograph p;
    p.data = &data;
    if (const PantographModelEntry* entry = find_pantograph_model(data.model))
      p.model = entry->create(data.parameters);
    p.motion = data.parameters.motion();
    const std::string number = n == 1 ? "" : " " + std::to_string(k + 1);
    p.block = "pantograph" + number;
    p.contact = "contact" + number;
    p.column_suffix = n == 1 ? "" : "[" + std::to_string(k + 1) + "]";
    list.push_back(std::move(p));
  }
  return list;
}

BlockOperator* SceneAssembly::body(const std::string& name)
{
  for (BlockOperator& b : bodies)
    if (b.name == name)
      return &b;
  return nullptr;
}

BlockOperator* SceneAssembly::wire_body(const Wire wire)
{
  return body(space().wire_block_name(wire));
}

BlockOperator* SceneAssembly::stitch_body()
{
  return body(space().stitch_block_name());
}

std::string SceneAssembly::constraint_name(const std::string& name) const
{
  return catenary().name.empty() ? name : catenary().name + " " + name;
}

const WireParameters& SceneAssembly::wire_parameters(const Wire wire) const
{
  return wire == Wire::carrier ? catenary().carrier : catenary().contact_wire;
}

void SceneAssembly::add_wire_body(const Wire wire, const bool with_bending)
{
  BlockOperator op;
  space().initialize_operator(wire, with_bending, op);
  WireTerms mass;
  mass.mass = wire_parameters(wire).mass_per_length;
  space().add_terms(wire, mass, op);
  bodies.push_back(std::move(op));
}

void SceneAssembly::add_wire_terms(const Wire wire, const WireTerms& terms)
{
  if (BlockOperator* b = wire_body(wire))
    space().add_terms(wire, terms, *b);
}

std::string SceneAssembly::load_shape() const
{
  if (space().discretisation_parameters().load_shape == LoadShape::point)
    return "point load (15)/(16)";
  return "smoothed delta_eps (25), eps = " +
         number_to_string(space().smoothed_delta().epsilon()) + " m";
}

SparseRow SceneAssembly::wire_row(const Wire wire, const double x) const
{
  return wire_point_row(space(), system, wire, x);
}

namespace
{
/// M or K += c H^T H on the body's sparsity (the entries of one cell).
void add_outer_product(dealii::SparseMatrix<double>& matrix, const SparseRow& h,
                       const double c)
{
  for (std::size_t i = 0; i < h.size(); ++i)
    for (std::size_t j = 0; j < h.size(); ++j)
      matrix.add(h.index[i], h.index[j], c * h.value[i] * h.value[j]);
}

/// m H^T H in the mass of @p b, lumped to m H_i on the diagonal of a diagonal one.
void add_mass(BlockOperator* b, const SparseRow& h, const double m)
{
  if (b == nullptr || m == 0.)
    return;
  if (b->mass_is_diagonal)
    for (std::size_t i = 0; i < h.size(); ++i)
      b->mass.add(h.index[i], h.index[i], m * h.value[i]);
  else
    add_outer_product(b->mass, h, m);
}
} // namespace

void SceneAssembly::add_point_mass(const Wire wire, const double x, const double m)
{
  if (BlockOperator* b = wire_body(wire))
    add_mass(b, space().point_row(wire, x), m);
}

void SceneAssembly::add_point_spring(const Wire wire, const double x, const double k)
{
  if (BlockOperator* b = wire_body(wire))
    add_outer_product(b->stiffness, space().point_row(wire, x), k);
}

void SceneAssembly::add_point_force(const Wire wire, const double x, const double force)
{
  if (BlockOperator* b = wire_body(wire))
    space().point_row(wire, x).add_transpose_to(b->load, force);
}

SparseRow SceneAssembly::dropper_upper_row(const unsigned int j) const
{
  return pantocat::dropper_upper_row(space(), system, j);
}

void SceneAssembly::add_at_dropper_top(const unsigned int j, const double force,
                                       const double m)
{
  const unsigned int s = catenary().stitch_wire_of(j);
  const double x = catenary().dropper_positions[j];
  if (s == no_stitch_wire)
  {
    add_point_force(Wire::carrier, x, force);
    add_point_mass(Wire::carrier, x, m);
    return;
  }
  BlockOperator* b = stitch_body();
  if (b == nullptr)
    return;
  const SparseRow h = space().stitch_wires().point_row(s, x);
  h.add_transpose_to(b->load, force);
  add_mass(b, h, m);
}
} // namespace pantocat
