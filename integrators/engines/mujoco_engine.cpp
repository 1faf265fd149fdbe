// MuJoCo 2.2.2 (libmujoco-dev) on the spheres-on-a-line scenes. Each sphere is a body on one
// slide joint along the axis (1 degree of freedom, so the scene's motion is all MuJoCo has), the
// floor a plane. Two settings:
//   mujoco         MuJoCo's defaults at the scene's step: solref (0.02, 1), solimp (0.9, 0.95,
//                  0.001), condim 3, the semi-implicit Euler integrator. What a user gets; it
//                  knows nothing of the scene's restitution (with it the ball barely bounces).
//   mujoco-spring  the scene's linear law as MuJoCo's direct spring-damper: solref = (-k w, -c w)
//                  per unit constraint mass (w the contact's inverse mass, models/engine_conventions),
//                  solimp dmin = dmax = 0.9999 (MuJoCo's largest impedance, so the constraint
//                  follows the reference almost exactly), frictionless (condim 1). MuJoCo's contact
//                  force is clamped at >= 0: the no-pull Kelvin-Voigt law.
// 2.2.2 loads XML from a file or its virtual file system, not a string: the model goes through
// the latter. Its contact and constraint buffers are fixed when the model is made (100 contacts
// and 500 constraint rows unless the XML says otherwise): a scene with more contacts is given
// room for all of them, as a user building it would (MuJoCo's warning says to), and a buffer that
// still fills ends the run as a typed failure with MuJoCo's warning. A full buffer drops contacts:
// a 1000-ball column's top ball fell freely through the rest (sink g t^2 / 2), and MuJoCo's
// default warning handler wrote MUJOCO_LOG.TXT into the working directory, which is now left
// to the run's own report.
#include "engine_world.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace contact {

namespace {

// MuJoCo 2.2.2's buffer sizes when the XML gives none.
constexpr std::size_t kMujocoContacts = 100, kMujocoRows = 500;

// MuJoCo's warnings are read from mjData after each step (below); its default handler would also
// print them and append them to MUJOCO_LOG.TXT in the working directory.
void quiet_warning(const char*) {}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

// MuJoCo's buffers, memory not physics (a full one is a warning, so a failed run, below): its own
// sizes, 100 contacts and 500 rows, made a small scene's world take six times as long to build (its
// stack is sized from them), and they do not suffice for a long chain. The spring setting's
// contacts are the scene's pairs, one row each (condim 1). At the defaults MuJoCo collides every
// pair of geoms, and its soft contacts let a column sink until spheres that are not neighbours
// overlap (40 spheres of 2 mm did): room for every pair, up to MuJoCo's own sizes, and at least
// the scene's pairs, each at most 4 rows (condim 3's pyramid).
std::string buffer_sizes(const EngineScene& s, bool spring) {
  const std::size_t pairs = std::max<std::size_t>(s.law.size(), 1), spheres = s.layout.mass.size();
  const std::size_t geom_pairs = spheres * (spheres - 1) / 2 + (s.layout.floor ? spheres : 0);
  std::size_t contacts = pairs, rows = pairs;  // the spring setting's
  if (!spring) {
    contacts = std::max(pairs, std::min(geom_pairs, kMujocoContacts));
    // From MuJoCo's own 100 contacts on, at least its own 500 rows.
    rows = contacts < kMujocoContacts ? 4 * contacts : std::max(kMujocoRows, 4 * contacts);
  }
  return fmt::format(R"(<size nconmax="{}" njmax="{}"/>)", contacts, rows);
}

// Geoms are named g<b> for sphere b and "floor". At the defaults MuJoCo finds contacts itself;
// the spring setting lists each contact as an explicit pair with its own solref (one per contact:
// a pair of spheres has half the constraint mass of a sphere on the floor) and turns the geoms'
// own collision off, as MuJoCo would otherwise mix the geoms' settings.
std::string scene_xml(const EngineScene& s, bool spring) {
  const SphereLineLayout& l = s.layout;
  std::string xml =
      fmt::format(R"(<mujoco model="contact-ode"><option timestep="{:.17g}" gravity="0 0 {:.17g}"/>)", s.dt,
                  l.vertical ? -l.g : 0.0);
  xml += buffer_sizes(s, spring);
  const char* own_collision = spring ? R"( contype="0" conaffinity="0")" : "";
  xml += "<worldbody>";
  if (l.floor) xml += fmt::format(R"(<geom name="floor" type="plane" size="10 10 0.1"{}/>)", own_collision);
  for (std::size_t b = 0; b < l.mass.size(); ++b)
    xml += fmt::format(R"(<body pos="{:.17g} 0 {:.17g}"><joint type="slide" axis="{}"/>)"
                       R"(<geom name="g{}" type="sphere" size="{:.17g}" mass="{:.17g}"{}/></body>)",
                       l.vertical ? 0.0 : s.centre[b], l.vertical ? s.centre[b] : 1.0,
                       l.vertical ? "0 0 1" : "1 0 0", b, l.radius, l.mass[b], own_collision);
  xml += "</worldbody>";
  if (spring) {
    xml += "<contact>";
    for (std::size_t c = 0; c < s.law.size(); ++c) {
      const auto [a, b] = s.bodies(c);
      xml += fmt::format(
          R"(<pair geom1="{}" geom2="g{}" condim="1" solref="{:.17g} {:.17g}" solimp="0.9999 0.9999 0.001"/>)",
          a < 0 ? std::string("floor") : fmt::format("g{}", a), b, -s.law[c].k * s.inverse_mass[c],
          -s.law[c].c * s.inverse_mass[c]);
    }
    xml += "</contact>";
  }
  return xml + "</mujoco>";
}

class MujocoWorld final : public EngineWorld {
 public:
  MujocoWorld(const EngineScene& s, bool spring) : scene_(s) {
    static std::once_flag quiet;
    std::call_once(quiet, [] { mju_user_warning = quiet_warning; });
    const std::string xml = scene_xml(s, spring);
    std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
    mj_defaultVFS(vfs.get());
    if (mj_makeEmptyFileVFS(vfs.get(), "scene.xml", static_cast<int>(xml.size())) != 0)
      throw std::runtime_error("MuJoCo: cannot make a file in its virtual file system");
    const int file = mj_findFileVFS(vfs.get(), "scene.xml");
    if (file < 0) throw std::runtime_error("MuJoCo: the file just made is not in its virtual file system");
    std::memcpy(vfs->filedata[file], xml.data(), xml.size());
    char error[1000] = "";
    model_.reset(mj_loadXML("scene.xml", vfs.get(), error, sizeof error));
    if (!model_)  // its constraint matrices are dense: (4 n)^2 numbers for n contacts (n = 1e4: 13 GB)
      throw EngineError(
          fmt::format("MuJoCo could not load the scene ({} contacts): {}", s.law.size(), error));
    data_.reset(mj_makeData(model_.get()));
    if (!data_) throw std::runtime_error("MuJoCo: mj_makeData returned NULL");
    for (std::size_t b = 0; b < s.velocity.size(); ++b) data_->qvel[b] = s.velocity[b];
  }

  void step(double h) override {
    model_->opt.timestep = h;
    mj_step(model_.get(), data_.get());
    // A full buffer drops contacts, and a bad number (NaN or past 1e10 in qpos, qvel or qacc) makes
    // MuJoCo reset the simulation to its initial state and go on: either way the run's answer is
    // no longer the scene's.
    for (int w = 0; w < mjNWARNING; ++w)
      if (data_->warning[w].number > 0)
        throw EngineError(fmt::format("MuJoCo: {}", mju_warningText(w, data_->warning[w].lastinfo)));
  }

  void read(std::vector<double>& centre, std::vector<double>& velocity) const override {
    const std::size_t n = scene_.centre.size();
    centre.resize(n);
    velocity.resize(n);
    for (std::size_t b = 0; b < n; ++b) {
      centre[b] = scene_.centre[b] + data_->qpos[b];  // the joint's displacement from the body's place
      velocity[b] = data_->qvel[b];
    }
  }

  // The contacts of the last mj_step were found and their forces solved at the step's start;
  // semi-implicit Euler applies those forces over the step.
  void impulses(std::vector<double>& impulse) const override {
    std::fill(impulse.begin(), impulse.end(), 0.0);
    const int floor = scene_.layout.floor ? 1 : 0;
    for (int j = 0; j < data_->ncon; ++j) {
      const mjContact& con = data_->contact[j];
      const int c = scene_.contact_between(con.geom1 - floor, con.geom2 - floor);
      if (c < 0 || con.efc_address < 0) continue;
      mjtNum force[6];
      mj_contactForce(model_.get(), data_.get(), j, force);
      impulse[static_cast<std::size_t>(c)] += force[0] * model_->opt.timestep;
    }
  }

 private:
  EngineScene scene_;
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
};

}  // namespace

// A MuJoCo model and data hold 250 to 336 doubles per state entry (chains of 5e4 and 1e5 balls).
constexpr double kMujocoWorkingDoubles = 448;

std::vector<MethodInfo> mujoco_methods() {
  return {
      engine_method("mujoco",
                    "MuJoCo 2.2.2 at its defaults: soft contacts solref (0.02, 1), semi-implicit Euler",
                    false, kMujocoWorkingDoubles,
                    [](const EngineScene& s) { return std::make_unique<MujocoWorld>(s, false); }),
      engine_method("mujoco-spring",
                    "MuJoCo 2.2.2 tuned to the scene's spring-damper: solref (-k w, -c w), impedance 0.9999 "
                    "(contacts only push: a Kelvin-Voigt law acts clamped)",
                    true, kMujocoWorkingDoubles,
                    [](const EngineScene& s) { return std::make_unique<MujocoWorld>(s, true); })};
}

}  // namespace contact
