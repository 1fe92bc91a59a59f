#include <pantocat/base/number_format.h>
#include <pantocat/coupling/wire_point_marker.h>
#include <pantocat/scene/moving_force.h>

namespace pantocat
{
namespace
{
/// F F_w(t)^T: the load row of the load shape at x_p(t) (a WirePointMarker), scaled.
class MovingLoad : public TimeDependentLoad
{
public:
  MovingLoad(WirePointMarker point, const double force)
      : point(std::move(point)), force(force)
  {
  }
  void add_to(const double t, dealii::Vector<double>& f) const override
  {
    point.row(t, row);
    for (std::size_t k = 0; k < row.size(); ++k)
      f(row.index[k]) += force * row.value[k];
  }

private:
  WirePointMarker point;
  double force;
  mutable SparseRow row; ///< scratch: no allocation per step
};
} // namespace

std::string MovingForce::name() const
{
  return "moving force";
}

bool MovingForce::enabled(const SceneParameters& scene, const CatenaryParameters&) const
{
  return scene.has_moving_force();
}

void MovingForce::add_constraints(SceneAssembly& a) const
{
  // One section (Case::check() refuses a moving force on a line of several).
  const CatenaryDiscretisation& space = *a.sections.front().space;
  const unsigned int wire =
      a.system.block(space.wire_block_name(Wire::contact_wire)).first;
  for (const ScenePantograph& p : a.pantographs)
    if (p.data->is_moving_force())
      a.system.add_time_dependent_load(std::make_unique<MovingLoad>(
          WirePointMarker(space, wire, p.motion), p.data->moving_force));
}

std::string MovingForce::describe(const SceneAssembly& a) const
{
  std::string line;
  for (const ScenePantograph& p : a.pantographs)
    if (p.data->is_moving_force())
      line += (line.empty() ? "" : "; ") + std::string("moving force: ") +
              number_to_string(p.data->moving_force) +
              " N at v_p = " + number_to_string(p.motion.speed) + " m/s, " +
              a.load_shape();
  return line;
}
} // namespace pantocat
