/* -*- c++ -*- ---------------------------------------------------------
   tribolmp MCA plugin: compute mca/atom

   One column of fix mca/state's per-automaton state as a per-atom vector,
   for decks that expect a per-atom compute (e.g. the links per automaton
   dumped as c_nbond):
     compute ID group mca/atom sxx|syy|szz|sxy|sxz|syz|eps_p|links|cross_links|seq
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(mca/atom,ComputeMCAAtom);
// clang-format on
#else

#ifndef TRIBOLMP_COMPUTE_MCA_ATOM_H
#define TRIBOLMP_COMPUTE_MCA_ATOM_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeMCAAtom : public Compute {
 public:
  ComputeMCAAtom(class LAMMPS *, int, char **);
  ~ComputeMCAAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  int column;
  int nmax;
  double *vec;
};

}    // namespace LAMMPS_NS

#endif
#endif
