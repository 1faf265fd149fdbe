// ODE 0.16 in double precision (libode-dev) on the spheres-on-a-line scenes: bodies with sphere
// geoms in a simple space, a plane for the floor, frictionless contact joints made each step
// from dCollide and solved by dWorldStep (ODE's direct LCP step). The spheres stay on the axis by
// symmetry: every contact normal joins two centres on it (or is the floor's), and without
// friction nothing turns them. Two settings:
//   ode         the world's defaults (ERP 0.2, CFM 1e-10 in double) with bounce = the scene's
//               restitution and no bounce threshold: Newton's law plus Baumgarte's push-out.
//               dWorldStep's pivoting LCP solver stops with "LCP internal error" on contacts
//               that touch at rest (a degenerate LCP: a touching cradle, a resting column);
//               the run then ends as a typed failure with ODE's message.
//   ode-quick   the same contacts stepped by dWorldQuickStep (20 projected Gauss–Seidel
//               iterations), the stepper ODE recommends for stacks.
//   ode-spring  the scene's spring-damper as the contact's soft ERP and CFM at the step
//               (erp = h k / (h k + c), cfm = 1 / (h k + c), models/engine_conventions): ODE's
//               own recipe for a spring, which it integrates by implicit Euler (first order,
//               numerically damped), no bounce.
#include "engine_world.hpp"

#include "contact_ode/models/engine_conventions.hpp"

#include <fmt/format.h>
#include <ode/ode.h>

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

#include <stdexcept>
#include <vector>

namespace contact {

namespace {

// ODE reports through handlers: a message (dMessage: a step it could not solve, such as "LCP
// internal error") is kept and turned into an EngineError after the step; an error or a debug
// assertion (dError, dDebug) would abort the process once its handler returns, so that handler
// throws, the only way out of it.
thread_local std::string ode_message;

void keep_message(int num, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  ode_message = fmt::format("ODE message {}: {}", num, text);
}

[[noreturn]] void throw_error(int num, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  throw EngineError(fmt::format("ODE error {}: {}", num, text));
}

// ODE keeps process-wide state: the random generator that QuickStep shuffles its constraints by
// (reseeded per world, drawn from at every step), the library's reference count and its handlers.
// Worlds stepped at once in two threads drew each other's numbers: of 24 engine solves run three
// at a time, ode and ode-quick gave three answers that differed from their serial runs. One ODE
// world exists at a time in a process; the other methods' solves still run side by side.
std::mutex& ode_in_use() {
  static std::mutex m;
  return m;
}

// dInitODE2/dCloseODE are reference-counted: one pair per world.
class OdeLibrary {
 public:
  OdeLibrary() {
    if (!dInitODE2(0)) throw std::runtime_error("ODE: dInitODE2 failed");
    dSetMessageHandler(keep_message);
    dSetErrorHandler(throw_error);
    dSetDebugHandler(throw_error);
  }
  ~OdeLibrary() {
    if (!abandoned_) dCloseODE();
  }
  // After an error inside a step ODE's threading state is inconsistent and dCloseODE asserts
  // (in a destructor: std::terminate); the reference is kept instead.
  void abandon() { abandoned_ = true; }
  OdeLibrary(const OdeLibrary&) = delete;
  OdeLibrary& operator=(const OdeLibrary&) = delete;

 private:
  bool abandoned_ = false;
};

class OdeWorld final : public EngineWorld {
 public:
  OdeWorld(const EngineScene& s, bool spring, bool quick) : scene_(s), spring_(spring), quick_(quick) {
    world_ = dWorldCreate();
    // A hash space: the simple space tests every pair of geoms every step (a 1e5-ball chain took
    // 67 s for one step, 0.9 s now). The pairs it reports are the same; QuickStep's shuffle of
    // its constraints (below) gave the same answers on every study scene.
    space_ = dHashSpaceCreate(nullptr);
    joints_ = dJointGroupCreate(0);
    if (!world_ || !space_ || !joints_) throw std::runtime_error("ODE: could not create the world");
    // QuickStep visits its constraints in an order shuffled by ODE's one global generator, which
    // runs on from whatever stepped before in the process: the same ode-quick run twice gave two
    // answers (a stack's velocities 10x apart). Reseeded per world, a run is its own.
    dRandSetSeed(0);
    const SphereLineLayout& l = s.layout;
    const int a = l.vertical ? 2 : 0;  // the axis's coordinate
    dWorldSetGravity(world_, 0, 0, l.vertical ? -l.g : 0.0);
    if (l.floor) {
      floor_ = dCreatePlane(space_, 0, 0, 1, 0);
      dGeomSetData(floor_, nullptr);
    }
    for (std::size_t b = 0; b < l.mass.size(); ++b) {
      dBodyID body = dBodyCreate(world_);
      dMass mass;
      dMassSetSphereTotal(&mass, l.mass[b], l.radius);
      dBodySetMass(body, &mass);
      dReal p[3] = {0, 0, 1}, v[3] = {0, 0, 0};
      p[a] = s.centre[b];
      v[a] = s.velocity[b];
      dBodySetPosition(body, p[0], p[1], p[2]);
      dBodySetLinearVel(body, v[0], v[1], v[2]);
      dBodySetAutoDisableFlag(body, 0);
      dGeomID geom = dCreateSphere(space_, l.radius);
      dGeomSetBody(geom, body);
      dGeomSetData(geom, reinterpret_cast<void*>(static_cast<std::intptr_t>(b + 1)));
      bodies_.push_back(body);
    }
    feedback_.reserve(s.restitution.size());  // at most one joint per contact and step
  }
  ~OdeWorld() override {
    // A world that an ODE error interrupted inside a step is left half-stepped, and destroying it
    // asserts again (e.g. "m_job_list == NULL" in its threading job list) inside an ODE
    // destructor, where our handler's throw is std::terminate. Such a world is leaked instead,
    // and so is the library's reference (dCloseODE asserts on the same state).
    if (interrupted_) {
      library_.abandon();
      return;
    }
    dJointGroupDestroy(joints_);
    dSpaceDestroy(space_);  // destroys its geoms
    dWorldDestroy(world_);  // and the bodies
  }
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  void step(double h) override {
    h_ = h;
    dJointGroupEmpty(joints_);
    feedback_.clear();
    made_.clear();
    ode_message.clear();
    try {  // an error in either leaves ODE's space or world half-way (the space locked)
      dSpaceCollide(space_, this, &OdeWorld::near);
      if (quick_)
        dWorldQuickStep(world_, h);
      else
        dWorldStep(world_, h);
    } catch (const EngineError&) {
      interrupted_ = true;
      throw;
    }
    if (!ode_message.empty()) throw EngineError(ode_message);
  }

  void read(std::vector<double>& centre, std::vector<double>& velocity) const override {
    const int a = scene_.layout.vertical ? 2 : 0;
    centre.resize(bodies_.size());
    velocity.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      centre[b] = dBodyGetPosition(bodies_[b])[a];
      velocity[b] = dBodyGetLinearVel(bodies_[b])[a];
    }
  }

  // The force each contact joint applied over the step, along its normal, times the step.
  void impulses(std::vector<double>& impulse) const override {
    std::fill(impulse.begin(), impulse.end(), 0.0);
    for (std::size_t k = 0; k < made_.size(); ++k) {
      // The force on the joint's first body; the floor's plane has none, and then the second's.
      const Made& m = made_[k];
      const dReal* f = m.first_body ? feedback_[k].f1 : feedback_[k].f2;
      impulse[m.contact] += std::abs(f[0] * m.normal[0] + f[1] * m.normal[1] + f[2] * m.normal[2]) * h_;
    }
  }

 private:
  struct Made {
    std::size_t contact;
    bool first_body;
    dReal normal[3];
  };

  // A sphere geom carries its index + 1 as its data; the floor's plane carries none (-1).
  static int sphere_of(dGeomID g) {
    return static_cast<int>(reinterpret_cast<std::intptr_t>(dGeomGetData(g))) - 1;
  }

  static void near(void* self, dGeomID g1, dGeomID g2) { static_cast<OdeWorld*>(self)->collide(g1, g2); }

  void collide(dGeomID g1, dGeomID g2) {
    const int c = scene_.contact_between(sphere_of(g1), sphere_of(g2));
    if (c < 0) return;
    dContact contact{};
    if (dCollide(g1, g2, 1, &contact.geom, sizeof(dContact)) < 1) return;
    const std::size_t i = static_cast<std::size_t>(c);
    contact.surface.mu = 0;
    if (spring_) {
      // ODE's spring constant is the force per unit overlap, whatever the masses.
      const OdeErpCfm soft = to_ode(scene_.law[i].k, scene_.law[i].c, h_);
      contact.surface.mode = dContactSoftERP | dContactSoftCFM;
      contact.surface.soft_erp = soft.erp;
      contact.surface.soft_cfm = soft.cfm;
    } else {
      contact.surface.mode = dContactBounce;
      contact.surface.bounce = scene_.restitution[i];
      contact.surface.bounce_vel = 0;
    }
    if (feedback_.size() == feedback_.capacity()) return;  // never: one joint per contact
    dJointID joint = dJointCreateContact(world_, joints_, &contact);
    dJointAttach(joint, dGeomGetBody(g1), dGeomGetBody(g2));
    feedback_.emplace_back();
    dJointSetFeedback(joint, &feedback_.back());
    made_.push_back({i,
                     dGeomGetBody(g1) != nullptr,
                     {contact.geom.normal[0], contact.geom.normal[1], contact.geom.normal[2]}});
  }

  std::lock_guard<std::mutex> one_world_at_a_time_{ode_in_use()};  // first: held until ODE is closed
  OdeLibrary library_;
  EngineScene scene_;
  bool spring_;
  bool quick_;
  bool interrupted_ = false;  // an ODE error ended a step half-way: the world is not destroyed
  double h_ = 0;              // the step being taken [s]: the soft contacts' ERP and CFM depend on it
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID joints_ = nullptr;
  dGeomID floor_ = nullptr;
  std::vector<dBodyID> bodies_;
  std::vector<dJointFeedback> feedback_;  // reserved: the joints keep pointers into it
  std::vector<Made> made_;
};

}  // namespace

// An ODE world holds 118 doubles per state entry and 0.0039 of a dense state-sized matrix (its step
// over one island of touching balls): 523 to 3237 doubles per entry on chains of 5e4 to 4e5 balls.
constexpr double kOdeWorkingDoubles = 160;
constexpr double kOdeDenseShare = 0.005;  // MethodInfo::dense_state_matrices

std::vector<MethodInfo> ode_engine_methods() {
  std::vector<MethodInfo> all = {
      engine_method("ode",
                    "ODE 0.16 (double) at its defaults (ERP 0.2) with bounce = e: Newton's law and Baumgarte",
                    false, kOdeWorkingDoubles,
                    [](const EngineScene& s) { return std::make_unique<OdeWorld>(s, false, false); }),
      engine_method("ode-quick",
                    "ODE 0.16 (double) as ode, stepped by dWorldQuickStep (20 Gauss-Seidel iterations)",
                    false, kOdeWorkingDoubles,
                    [](const EngineScene& s) { return std::make_unique<OdeWorld>(s, false, true); }),
      engine_method(
          "ode-spring",
          "ODE 0.16 (double) with the scene's spring-damper as soft ERP/CFM (implicit Euler; contacts "
          "only push: a Kelvin-Voigt law acts clamped)",
          true, kOdeWorkingDoubles,
          [](const EngineScene& s) { return std::make_unique<OdeWorld>(s, true, false); })};
  for (MethodInfo& info : all) info.dense_state_matrices = kOdeDenseShare;
  return all;
}

}  // namespace contact
