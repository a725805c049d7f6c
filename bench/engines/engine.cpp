#include "engine.h"

#include <stdexcept>

namespace chainbench {

std::unique_ptr<Engine> make_chain_engine(const EngineSpec& spec, const Scene& scene);
std::unique_ptr<Engine> make_box2d_engine(const EngineSpec& spec, const Scene& scene);

std::unique_ptr<Engine> make_engine(const EngineSpec& spec, const Scene& scene) {
  if (spec.engine == "chain") return make_chain_engine(spec, scene);
  if (spec.engine == "box2d") return make_box2d_engine(spec, scene);
  throw std::logic_error("make_engine: no adapter for " + spec.engine);
}

}  // namespace chainbench
