#pragma once
// What a scene offers the contact paradigms, as three capabilities: Dynamics (the ODE), ContactGeometry
// (gaps and penalty laws) and ImpulseMap (projection and impulses). A paradigm asks for the ones it
// needs (integrators/capabilities.hpp); a scene knows its physics and nothing of the integrator
// that runs it.
//
// State layout: position_mask() marks the positions; the other entries are velocities.
// Positions change only through the velocities (q' = Q(q) v), which is what semi-implicit
// schemes rely on. A scene may interleave them (x0, v0, x1, v1, ...) to keep its Jacobian banded.
//
// Contact modes: how each potential contact takes part in the dynamics right now.
//   Free     no contact force (free flight);
//   Penalty  the contact law's force, as a smooth extension (see contact_law.hpp);
//   Resting  held on the surface: the normal motion is frozen (event-driven rest after Zeno).
// Integrators that locate the switching roots pass the modes they hold; others use
// modes_from_state(), which reads them off the sign of each switching function.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/linear_algebra.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace contact {

enum class ContactMode : std::uint8_t { Free, Penalty, Resting };
using ContactModes = std::vector<ContactMode>;

// Dynamics: the ODE y' = f(t, y) of a scene with its contacts in given modes. All a fixed-step
// scheme or an ODE integrator needs; a scene without contacts (the free spring) offers only this.
class Dynamics {
 public:
  virtual ~Dynamics() = default;

  virtual std::string name() const = 0;
  virtual Mask position_mask() const = 0;
  virtual std::size_t state_size() const = 0;
  virtual Vector initial_state() const = 0;
  // Column names with units, one per state entry, e.g. "y_m", "v_mps".
  virtual std::vector<std::string> state_labels() const = 0;
  // How many potential contacts rhs() takes a mode for (0: none).
  virtual std::size_t contact_count() const { return 0; }

  // y' = f(t, y) with every contact in the given mode.
  virtual void rhs(double t, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const = 0;
  // Analytic df/dy for the same modes, sized state_size() square. Every entry of the pattern is
  // stored, zeros included, whatever the modes, so that sparse factorisations can reuse it; the
  // pattern includes the whole diagonal, which the Newton matrix I - gamma J needs (without it
  // SUNDIALS inserts the diagonal into the sparse arrays at every setup, an O(N nnz) shuffle that
  // made KLU quadratic in the chain's length).
  virtual void jacobian(double t, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const = 0;
  // Whether jacobian() is implemented; without it implicit integrators use difference quotients.
  virtual bool has_jacobian() const { return true; }
  // Restores invariants of the state a fixed-step method may drift off (unit quaternions).
  virtual void normalize(VectorRef) const {}
  // The band that holds every non-zero of the Jacobian (default: full).
  virtual Bandwidth jacobian_bandwidth() const {
    const auto n = static_cast<long>(state_size());
    return {n - 1, n - 1};
  }
  // Kinetic + potential + elastic energy of the engaged penalty springs [J]
  // (ContactGeometry::engaged_elastic_energy).
  virtual double energy(ConstVectorRef y) const = 0;
  // Kinetic + potential energy alone [J]: what a method without the contact springs (impulses,
  // constraints, an engine's own contacts) holds. Computed without them, not as energy() less
  // their energy: at an overlap of rounding size under a stiff law (1e-17 m at k = 1e300) the
  // springs' 1e268 J would swallow the motion's 0.05 J in the subtraction. A scene without contact
  // springs has nothing to leave out.
  virtual double energy_without_springs(ConstVectorRef y) const { return energy(y); }
  // The mean mass of the moving bodies [kg]: the unit in which a method keeps an energy it
  // integrates (the penalty's ledger, per kilogram), so that its error test, like the state's,
  // does not depend on the unit of mass.
  virtual double mean_mass() const = 0;

  ContactModes all_modes(ContactMode m) const { return ContactModes(contact_count(), m); }
};

// Contact geometry: where each potential contact i stands and what its penalty law does there.
// What the penalty paradigm and the game loop's detection need, beside the dynamics.
class ContactGeometry {
 public:
  virtual ~ContactGeometry() = default;
  // Signed gap along the contact normal [m]: > 0 apart, < 0 overlapping.
  virtual double gap(std::size_t i, ConstVectorRef y) const = 0;
  // Its time derivative [m/s]: < 0 approaching.
  virtual double gap_rate(std::size_t i, ConstVectorRef y) const = 0;
  // > 0 exactly while the penalty law of contact i pushes [m].
  virtual double switching(std::size_t i, ConstVectorRef y) const = 0;
  // Whether contact i's law can let go while the bodies still overlap (see contact_law.hpp);
  // if no contact's can, a penalty run needs no root for the overlap's closing.
  virtual bool releases_while_overlapping(std::size_t) const { return true; }
  // The overlap at which contact i's normal turns about [m]: two spheres' centres cross at the sum
  // of their radii. Infinite where it never does (a plane's normal, a signed gap along a line).
  virtual double overlap_extent(std::size_t) const { return std::numeric_limits<double>::infinity(); }
  // Power contact i's penalty law dissipates while in Penalty mode [W] (the energy ledger).
  virtual double dissipated_power(std::size_t i, ConstVectorRef y) const = 0;
  // Elastic energy contact i's law holds at the present overlap, whether or not it pushes [J].
  virtual double elastic_energy(std::size_t i, ConstVectorRef y) const = 0;

  // Contacts 0 .. d.size() - 1's gaps and gap rates (switching functions and gap rates) in one
  // call: what root functions read at every step (a penalty chain of 1000 balls made some five
  // indirect calls per contact and evaluation, 9 % of its run). By default contact by contact; a
  // scene may give them in one loop.
  virtual void gaps_and_rates(ConstVectorRef y, std::span<double> d, std::span<double> r) const {
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i] = gap(i, y);
      r[i] = gap_rate(i, y);
    }
  }
  virtual void switching_and_rates(ConstVectorRef y, std::span<double> s, std::span<double> r) const {
    for (std::size_t i = 0; i < s.size(); ++i) {
      s[i] = switching(i, y);
      r[i] = gap_rate(i, y);
    }
  }

  // Penalty where the switching function is positive, free elsewhere, for contacts 0..count-1;
  // fills `modes` in place so that callers inside a step loop allocate nothing.
  void modes_from_state(std::size_t count, ConstVectorRef y, ContactModes& modes) const {
    modes.resize(count);
    for (std::size_t i = 0; i < count; ++i)
      modes[i] = switching(i, y) > 0 ? ContactMode::Penalty : ContactMode::Free;
  }
  // The elastic energy of the contacts 0..count-1 whose law pushes (switching > 0) [J]: what
  // energy() counts. A clamped law (F = max(0, k d + c d')) lets go while the bodies still
  // overlap; the energy its spring held then is lost, a physical loss the penalty method books at
  // the release. Counting it until the overlap closes would book it as numerical drift instead.
  double engaged_elastic_energy(std::size_t count, ConstVectorRef y) const {
    double E = 0;
    for (std::size_t i = 0; i < count; ++i) E += counted_elastic_energy(i, y);
    return E;
  }
  // Contact i's share of it: its spring's energy while it overlaps and its law pushes, else 0.
  double counted_elastic_energy(std::size_t i, ConstVectorRef y) const {
    // (Every law's switching is at most the overlap -gap, so open contacts skip it.)
    return gap(i, y) < 0 && switching(i, y) > 0 ? elastic_energy(i, y) : 0.0;
  }
};

// The impulse map: impulsive resolution, the seed's way. What event-driven resolution and the game
// loop's projection and impulse need, beside the geometry.
class ImpulseMap {
 public:
  virtual ~ImpulseMap() = default;
  // Newton's restitution for contact i.
  virtual double restitution(std::size_t i) const = 0;
  // Projection: move the bodies apart along the normal, by inverse-mass share, until gap = 0.
  virtual void project(std::size_t i, VectorRef y) const = 0;
  // Impulse J = -(1+e) v_r.n / (sum of inverse masses [+ angular terms]) along the normal; returns
  // J [N s]. Methods apply it where the contact approaches; where it does not, the rigid scenes
  // return 0 and the line models (drop, chain, column) apply the formula as it stands, a pull
  // (their settle stops a parting pair with it, at e = 0). The kinetic energy it takes is then
  // -J (u- + u+) / 2 exactly, u the gap rate before and after (the energy is quadratic in the
  // velocities, which J changes by M^-1 G^T J): a method books it without the whole scene's energy.
  virtual double apply_impulse(std::size_t i, double e, VectorRef y) const = 0;
  // Put contact i at rest on its surface (gap 0, no normal velocity).
  virtual void settle(std::size_t i, VectorRef y) const = 0;
  // Whether contact i at rest is held by the dynamics (a support: the floor, a static body), or
  // only marked at rest while its bodies move as free (two moving bodies).
  virtual bool holds_at_rest(std::size_t) const { return true; }
};

// A scene with unilateral contacts that every paradigm can run: dynamics, contact geometry and
// impulse map together.
class MechanicalSystem : public Dynamics, public ContactGeometry, public ImpulseMap {
 public:
  std::size_t contact_count() const override = 0;
  void modes_from_state(ConstVectorRef y, ContactModes& modes) const {
    ContactGeometry::modes_from_state(contact_count(), y, modes);
  }
  double engaged_elastic_energy(ConstVectorRef y) const {
    return ContactGeometry::engaged_elastic_energy(contact_count(), y);
  }
};

// The state of n bodies moving along one line, interleaved (u0, v0, u1, v1, ...): its position
// mask and its labels "u<b>_m", "v<b>_mps".
Mask interleaved_positions(std::size_t n);
std::vector<std::string> interleaved_labels(std::size_t n);

// A scene whose contacts all follow one penalty law of their gap: the law's switching function,
// dissipated power and stored energy at overlap -gap and overlap rate -gap_rate.
class OneLawSystem : public MechanicalSystem {
 public:
  explicit OneLawSystem(const ContactLaw& law) : law_(law) {}
  double switching(std::size_t i, ConstVectorRef y) const override {
    return contact::switching(law_, -gap(i, y), -gap_rate(i, y));
  }
  bool releases_while_overlapping(std::size_t) const override {
    return contact::releases_while_overlapping(law_);
  }
  double dissipated_power(std::size_t i, ConstVectorRef y) const override {
    return contact::dissipated_power(law_, -gap(i, y), -gap_rate(i, y));
  }
  double elastic_energy(std::size_t i, ConstVectorRef y) const override {
    return stored_energy(law_, -gap(i, y));
  }
  // From gaps_and_rates, the law dispatched once: the same values as switching() and gap_rate().
  void switching_and_rates(ConstVectorRef y, std::span<double> s, std::span<double> r) const override;

 protected:
  // gaps_and_rates for a final scene, its gap() and gap_rate() called without dispatch.
  template <class Scene>
  static void direct_gaps_and_rates(const Scene& scene, ConstVectorRef y, std::span<double> d,
                                    std::span<double> r) {
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i] = scene.Scene::gap(i, y);
      r[i] = scene.Scene::gap_rate(i, y);
    }
  }

 private:
  ContactLaw law_;
};

// Optional capability: normal impulses of any size, and the same along the positions. What the
// time-stepping solvers engines use (sequential impulses, soft step, XPBD, Moreau–Jean) need
// beside the geometry: with J_i the row that maps velocities to contact i's gap rate and M the
// mass matrix, w_i = J_i M^-1 J_i^T, and an impulse lambda changes the velocities by
// M^-1 J_i^T lambda (so contact i's gap rate by w_i lambda).
class NormalImpulses {
 public:
  virtual ~NormalImpulses() = default;
  // w_i [1/kg]: the change of contact i's gap rate per unit impulse along its normal.
  virtual double inverse_mass(std::size_t i, ConstVectorRef y) const = 0;
  // Velocities += M^-1 J_i^T lambda [N s]; lambda > 0 pushes the bodies apart.
  virtual void apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const = 0;
  // Positions += M^-1 J_i^T dlambda [kg m]: the same map applied to a position correction (XPBD).
  virtual void apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const = 0;
  // Contact i's penalty law when it is linear (F = k delta + c delta'), else NaN in both: the
  // spring a compliant constraint (XPBD) matches.
  virtual LinearLaw linear_law(std::size_t i) const = 0;
};

// Optional capability: the scene as equal spheres whose centres move along one axis, what an
// external physics engine (integrators/engines) is given to build its own world. The state must
// be interleaved (u_0, v_0, u_1, v_1, ...): sphere b's centre is rest_centre[b] + u_b along the
// axis, its velocity v_b. Contacts join neighbours: with a floor, contact 0 is floor - sphere 0
// and contact c > 0 joins spheres c-1 and c; without one, contact c joins spheres c and c+1.
struct SphereLineLayout {
  double radius = 0.05;  // every sphere's [m]; a point-mass scene picks one (rotation never enters)
  bool vertical = true;  // the axis is vertical (gravity g acts along -axis) or horizontal (none along it)
  double g = 0;          // [m/s^2]
  bool floor = false;    // a fixed plane at coordinate 0, normal +axis, below sphere 0
  std::vector<double> mass;         // per sphere [kg]
  std::vector<double> rest_centre;  // sphere b's centre coordinate when u_b = 0 [m]
};
class SphereLine {
 public:
  virtual ~SphereLine() = default;
  virtual SphereLineLayout sphere_line() const = 0;
};

// Optional capability: free flight known in closed form (e.g. a point mass under uniform
// gravity). Event-driven resolution uses it as the exact reference flight.
class AnalyticFlight {
 public:
  virtual ~AnalyticFlight() = default;
  // State after flying freely for dt from y0.
  virtual void propagate(ConstVectorRef y0, double dt, VectorRef y) const = 0;
  // Time until contact i's gap next reaches zero while approaching; +inf if never.
  virtual double time_to_impact(std::size_t i, ConstVectorRef y0) const = 0;
  // Time until contact i's gap rate next falls through zero (an apex); +inf if never.
  virtual double time_to_apex(std::size_t i, ConstVectorRef y0) const = 0;
};

}  // namespace contact
