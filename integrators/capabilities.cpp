#include "contact_ode/integrators/capabilities.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace contact {

namespace {

// Never asked: a scene without contacts has no contact index to ask about.
class NoContacts final : public ContactGeometry {
 public:
  double gap(std::size_t, ConstVectorRef) const override { return 0.0; }
  double gap_rate(std::size_t, ConstVectorRef) const override { return 0.0; }
  double switching(std::size_t, ConstVectorRef) const override { return 0.0; }
  double dissipated_power(std::size_t, ConstVectorRef) const override { return 0.0; }
  double elastic_energy(std::size_t, ConstVectorRef) const override { return 0.0; }
};

}  // namespace

const ContactGeometry& contact_geometry(const Dynamics& scene) {
  if (const auto* g = dynamic_cast<const ContactGeometry*>(&scene)) return *g;
  if (scene.contact_count() != 0)
    throw std::invalid_argument(fmt::format("scene '{}' has {} contacts but no contact geometry",
                                            scene.name(), scene.contact_count()));
  static const NoContacts none;
  return none;
}

bool has_impulse_map(const Dynamics& scene) { return dynamic_cast<const ImpulseMap*>(&scene) != nullptr; }

const ImpulseMap& impulse_map(const Dynamics& scene, std::string_view method) {
  if (const auto* m = dynamic_cast<const ImpulseMap*>(&scene)) return *m;
  throw std::invalid_argument(fmt::format(
      "method '{}' resolves contacts by impulses, and scene '{}' has no impulse map", method, scene.name()));
}

bool has_normal_impulses(const Dynamics& scene) {
  return dynamic_cast<const NormalImpulses*>(&scene) != nullptr &&
         dynamic_cast<const ContactGeometry*>(&scene);
}

bool has_linear_laws(const Dynamics& scene) {
  if (!has_normal_impulses(scene)) return false;
  const auto& normal = dynamic_cast<const NormalImpulses&>(scene);
  for (std::size_t i = 0; i < scene.contact_count(); ++i)
    if (!(normal.linear_law(i).k > 0)) return false;
  return true;
}

const NormalImpulses& normal_impulses(const Dynamics& scene, std::string_view method) {
  if (const auto* m = dynamic_cast<const NormalImpulses*>(&scene)) return *m;
  throw std::invalid_argument(fmt::format(
      "method '{}' solves for normal impulses, and scene '{}' offers none", method, scene.name()));
}

}  // namespace contact
