// The Box2D reference world behind the Engine interface.
#include "box2d_world.h"
#include "engine.h"

namespace chainbench {
namespace {

Box2dSettings settings(const EngineSpec& spec) {
  Box2dSettings s;
  s.velocity_iterations = static_cast<int>(spec.get_int("vel_iters"));
  s.position_iterations = static_cast<int>(spec.get_int("pos_iters"));
  s.substeps = static_cast<int>(spec.get_int("substeps"));
  s.compensate_skin = spec.get("skin") == "compensate";
  s.warm_starting = spec.get_int("warm") != 0;
  return s;
}

class Box2dEngine final : public Engine {
 public:
  Box2dEngine(const EngineSpec& spec, const Scene& scene) : world_(scene, settings(spec)) {}
  void step(int step_index) override { world_.step(step_index); }
  void read_state(BodyState& out) const override {
    world_.read_state(out.position, out.velocity, out.angle);
  }

 private:
  Box2dWorld world_;
};

}  // namespace

std::unique_ptr<Engine> make_box2d_engine(const EngineSpec& spec, const Scene& scene) {
  return std::make_unique<Box2dEngine>(spec, scene);
}

}  // namespace chainbench
