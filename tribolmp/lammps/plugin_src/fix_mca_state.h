/* -*- c++ -*- ---------------------------------------------------------
   tribolmp MCA plugin: fix mca/state

   Per-automaton and per-link state of pair style mca, stored with the atoms
   so that it follows them through MPI exchange and is written to / read from
   restart files (the role fix neigh/history plays for pair granular).

   Each atom keeps up to maxpartner "slots", one per linked or touching
   partner.  Both automata of a pair keep a copy of the pair's state, in the
   canonical orientation (from the smaller to the larger atom ID), and update
   it with identical arithmetic (pair mca uses a full neighbour list), so no
   reverse communication is needed.

   Syntax:  fix mca_state all mca/state [maxpartner N]
   (pair style mca creates it with this ID if the deck does not.)
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(mca/state,FixMCAState);
// clang-format on
#else

#ifndef TRIBOLMP_FIX_MCA_STATE_H
#define TRIBOLMP_FIX_MCA_STATE_H

#include "fix.h"

namespace LAMMPS_NS {

class FixMCAState : public Fix {
 public:
  // slot layout (doubles): partner tag, kind, p_n, xi[3], theta_rel[3], R_prev[3].  (Until
  // 2026-12-02 two more: the link damping constants, now recomputed from the two automata's
  // masses and radii, mca_law.h link_damping; a restart file of 14-value slots is refused.)
  enum { S_TAG = 0, S_KIND, S_PN, S_XI, S_TH = S_XI + 3, S_RP = S_TH + 3, NSLOT = S_RP + 3 };
  enum { FREE = 0, LINK = 1, WELD = 2, CONTACT = 3, ATTACH = 4 };
  // automaton layout: stress[6], eps_eq, n_links, n_cross, von Mises stress (these first
  // NOUT values are the fix's per-atom output, f_mca_state[1..10]: the fix hands LAMMPS the
  // rows themselves as its peratom array, so the output is never copied), eps_p tensor[6],
  // pending deps[6], X, counters[4] (cross formed, cross broken, links broken, welds formed),
  // X used by the forces of the last committed step (for re-evaluations), the pair force and
  // torque of the last committed step (restored by a re-evaluation).  (Until 2026-12-06 the
  // order was stress, eps_p tensor, eps_eq, deps, X, n_links, n_cross, counters, von Mises
  // stress, X used, force, torque, and the output a separate array written every step;
  // restart files in that order are read and reordered, unpack_restart.)
  enum {
    A_SIG = 0, A_EEQ = 6, A_NL = 7, A_NC = 8, A_SEQ = 9, A_EPT = 10, A_DEP = 16, A_X = 22,
    A_CF = 23, A_CB = 24, A_LB = 25, A_WF = 26, A_XU = 27, A_F = 28, A_T = 31, NAUTO = 34
  };
  // output columns (sxx syy szz sxy sxz syz eps_p links cross_links seq): the first NOUT
  // values of an automaton's row
  enum { NOUT = 10 };
  // per-atom restart record: its length, a layout tag, the slots, the automaton row.  The
  // tag marks the automaton order above; a record one value shorter (no tag) is the order
  // before 2026-12-06
  enum { RESTART_LAYOUT = 2 };

  FixMCAState(class LAMMPS *, int, char **);
  ~FixMCAState() override;
  int setmask() override;
  void init() override;

  void write_restart(FILE *) override;
  void restart(char *) override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

  int maxpartner;
  int initialized;          // 1 once the initial links have been made
  double last_commit;       // timestep of the last committed state update
  double **slots;           // [nmax][maxpartner*NSLOT]
  double **autom;           // [nmax][NAUTO] (its first NOUT columns: the peratom array)

  double *slot(int i, int k) { return &slots[i][k * NSLOT]; }

  // Deferred mirror copies.  A pair of two local automata is evaluated once, on the copy of
  // the automaton with the smaller ID; the partner's copy is brought up to date only when it
  // can be read: before atoms move in the arrays (exchange, sort, deletion), before a restart
  // is written, and before pair mca re-maps its slots after a neighbour-list rebuild.  Between
  // these points nothing reads it (the pair is not evaluated from the partner's side).  Pair
  // mca knows the pending pairs (its evaluation lists); this asks it to write them.  The same
  // call writes back the live pair states, which pair mca keeps in its own array in the order
  // of its evaluation lists between two rebuilds (PairMCA::psc): until then the slots of the
  // evaluating automata are behind as well.
  void sync_mirrors();
  int per_atom() const { return maxpartner * NSLOT + NAUTO; }

 private:
  int nmax_local;
};

}    // namespace LAMMPS_NS

#endif
#endif
