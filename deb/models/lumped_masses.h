// A one-dimensional network of point masses joined to each other and to the
// ground by springs and dampers: a payload on a flexure on an isolated table,
// a stage on its frame, a two-mass drive train. Engineers write these as
// masses, stiffnesses and damping coefficients; deb builds the state space
// (the path type `lumped_masses`, docs/budget_reference.md).
//
// Coordinates: each mass's displacement z_i = x_i - x_g relative to the
// ground, which may accelerate (a_g). With the mass, stiffness and damping
// matrices M, K, C assembled from the couplings (a coupling k between masses
// a and b adds k to K_aa and K_bb and -k to K_ab and K_ba; one to the ground
// adds k to K_aa only),
//   M z'' + C z' + K z = F - M 1 a_g,
// realised with states [z; z'] as A = [0 I; -M^-1 K  -M^-1 C]. SI units
// throughout: forces in N, the ground's acceleration in m/s^2, outputs in m
// (displacement) or m/s (velocity).
#pragma once

#include <string>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

struct LumpedMasses {
  static constexpr int kGround = -1;  // the index of the ground in couplings, inputs and outputs

  std::vector<std::string> names;  // one per mass, "ground" excluded
  std::vector<double> mass_kg;
  struct Coupling {
    int a = 0, b = kGround;     // the two ends: masses, or kGround
    double k_n_per_m = 0.0;      // spring
    double c_n_s_per_m = 0.0;    // viscous damper in parallel
  };
  std::vector<Coupling> couplings;

  // An input: a force F on mass `on` (and -F on `reaction`, an actuator
  // between two masses), or the ground's acceleration (on = kGround).
  struct Input {
    int on = kGround;
    int reaction = kGround;
  };
  // An output: the displacement (or velocity) of mass `of` less that of
  // `relative_to` (kGround: relative to the ground).
  struct Output {
    int of = 0;
    int relative_to = kGround;
    bool velocity = false;
  };

  // @throws InputError naming the offending mass or coupling: a mass not
  //         positive and finite, a stiffness or damping negative or not
  //         finite, a coupling of a mass to itself or with neither k nor c,
  //         an index out of range.
  void Validate() const;

  // The state space from `inputs` to `outputs`, 2 states per mass.
  // @throws InputError as Validate, or for an input or output that names a
  //         mass out of range or the same mass twice.
  StateSpace Realise(const std::vector<Input>& inputs, const std::vector<Output>& outputs) const;
};

}  // namespace deb
