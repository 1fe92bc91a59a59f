#include <pantocat/base/number_format.h>
#include <pantocat/scene/moving_force.h>

namespace pantocat
{
namespace
{
/// F F_w(t)^T: the load row r_0 of the load shape at x_p(t), scaled.
class MovingLoad : public TimeDependentLoad
{
public:
  MovingLoad(const CatenaryDiscretisation& space, const ContactPointMotion& motion,
             const double force, const unsigned int offset)
      : space(space), motion(motion), force(force), offset(offset)
  {
  }
  void add_to(const double t, dealii::Vector<double>& f) const override
  {
    space.load_row(motion.position(t), 0, row);
    for (std::size_t k = 0; k < row.size(); ++k)
      f(offset + row.index[k]) += force * row.value[k];
  }

private:
  const CatenaryDiscretisation& space;
  ContactPointMotion motion;
  double force;
  unsigned int offset;
  mutable SparseRow row; ///< scratch: no allocation per step
};
} // namespace

std::string MovingForce::name() const
{
  return "moving force";
}

bool MovingForce::enabled(const SceneParameters& scene) const
{
  return scene.pantograph == PantographType::moving_force;
}

void MovingForce::add_constraints(SceneAssembly& a) const
{
  a.system.add_time_dependent_load(std::make_unique<MovingLoad>(
      a.space, a.motion, a.scene.moving_force, a.system.block("contact wire").first));
}

std::string MovingForce::describe(const SceneAssembly& a) const
{
  return "moving force: " + number_to_string(a.scene.moving_force) +
         " N at v_p = " + number_to_string(a.motion.speed) + " m/s, " + a.load_shape();
}
} // namespace pantocat
