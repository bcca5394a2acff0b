/* -*- c++ -*- ---------------------------------------------------------
   tribolmp MCA plugin: fix nve/mca

   Velocity-Verlet update of position, velocity and angular velocity of
   finite-size spheres, for automata of pair style mca.  The arithmetic of
   every update is that of fix nve/bpm/sphere (same operations in the same
   order, so the same x, v, omega to the last bit), without the orientation
   quaternion: the mca law keeps relative rotations per link (integrated
   from omega in the pair state) and never reads an automaton's orientation,
   so the quaternion update (a third of the integrator's cost in 2D) is
   skipped.  Atom styles with radius, omega, torque and per-atom mass
   (sphere, bpm/sphere).

   Syntax:  fix ID group nve/mca [disc]
     disc: moment of inertia of a disc, m r^2 / 2 (2D only); default a
           sphere's, 2 m r^2 / 5 (what nve/bpm/sphere and nve/sphere use)
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(nve/mca,FixNVEMCA);
// clang-format on
#else

#ifndef TRIBOLMP_FIX_NVE_MCA_H
#define TRIBOLMP_FIX_NVE_MCA_H

#include "fix.h"

namespace LAMMPS_NS {

class FixNVEMCA : public Fix {
 public:
  FixNVEMCA(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void reset_dt() override;

 private:
  double inertia;    // moment of inertia / (m r^2)
  double dtv, dtf;
  template <bool MOVE> void kick();
};

}    // namespace LAMMPS_NS

#endif
#endif
