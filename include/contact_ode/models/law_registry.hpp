#pragma once
// Every contact law by name, with what it is tuned from. A new law is a value type in
// contact_law.hpp and one entry in law_registry.cpp; experiments, the advisor, tests and
// benchmarks enumerate laws from here only.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/parameters.hpp"

#include <functional>
#include <string>
#include <vector>

namespace contact {

// What a law is built from. Each law reads the fields that apply to it.
struct LawSpec {
  double k = 1e5;                          // stiffness [N/m], or K [N/m^n] for the power laws
  double m = 1.0;                          // effective mass of the contact [kg] (damping tuned for it)
  double e = 0.8;                          // target restitution (undamped laws ignore it)
  double v = 1.0;                          // impact speed the Hunt–Crossley damping is tuned at [m/s]
  DampingRule rule = kDefaultDampingRule;  // Hunt–Crossley damping rule
};

struct LawInfo {
  std::string name;
  std::string description;
  double exponent;           // n in F ~ delta^n
  bool damped;               // whether e shapes it
  bool pulls;                // whether its force can turn negative (an unclamped dashpot)
  std::string closed_forms;  // the closed forms analysis/references.hpp has for it
  std::vector<ParameterInfo> parameters;
  std::function<ContactLaw(const LawSpec&)> make;
};

const std::vector<LawInfo>& law_registry();
std::vector<std::string> law_names();
// Throws std::invalid_argument naming the accepted laws.
const LawInfo& law_info(const std::string& name);
ContactLaw make_law(const std::string& name, const LawSpec& spec);

}  // namespace contact
