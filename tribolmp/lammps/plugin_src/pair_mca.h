/* -*- c++ -*- ---------------------------------------------------------
   tribolmp MCA plugin: pair style mca

   Movable cellular automata (Psakhie, Popov et al.): a many-body elastic
   law (pair responses plus the automaton's mean stress, so that E and nu are
   independent), von Mises plasticity per automaton with radial return and
   isotropic hardening, links that break in tension/shear, unlinked contacts
   with repulsion, Coulomb friction and viscosity that weld when pressed,
   and rotational resistance of links.  The rules are in mca_law.h.

   Syntax:
     pair_style mca [link_init same|all|none|bonds] [link_tol X] [attach_type N] [cutoff F]
     pair_coeff * * G nu sigma_y sigma_0 H mu eta weld_factor weld_onset damp
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(mca,PairMCA);
// clang-format on
#else

#ifndef TRIBOLMP_PAIR_MCA_H
#define TRIBOLMP_PAIR_MCA_H

#include "mca_law.h"
#include "pair.h"

namespace LAMMPS_NS {

class PairMCA : public Pair {
 public:
  PairMCA(class LAMMPS *);
  ~PairMCA() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;
  void sync_mirrors();

  enum { NTALLY = 7 };

 protected:
  MCALaw::Material mat;
  int link_init;        // 0 none, 1 same molecule, 2 all, 3 the data file's bonds
  int attach_type;      // bond type that becomes an unbreakable attachment (link_init bonds)
  double link_tol;      // initial links: r < (1 + link_tol) dbar
  double cutfac;        // neighbour cutoff / (2 max radius)
  double maxrad;
  class FixMCAState *fix;
  int **cache;          // unused (kept for layout clarity)
  int *ncache;
  int maxcache_atoms;
  // evaluation lists (rebuild_cache): the pairs each local automaton evaluates, in the
  // neighbour list's order -- every ghost partner but its own image, and the local partners
  // with a larger ID
  enum { E_IA = 1, E_LOCAL = 2, E_IMAGE = 4, E_SAME = 8 };    // i is a; j local; image; same body
  int *ej;              // partner index
  int *eflag;           // E_* bits
  int *cacheflat;       // slot index of i for the pair (-1: none)
  int *mirrorflat;      // local partner: its slot for i (-1: none)
  bigint *cacheoff;     // offset of atom i's pairs (-1: none)
  int *ecount;          // number of atom i's pairs
  int ncached;          // local atoms when the lists were built
  int mirrors_pending;  // 1: the partners' copies of local pairs are behind (sync_mirrors)
  bigint maxflat;
  double **sacc;        // Love-Weber sums and link counts of local atoms
  int maxsacc;
  int coeffset;
  double **xo;          // owner coordinates and velocities (x, v) of local and ghost atoms
  double **pin;         // pair inputs of local and ghost atoms: X, pending plastic increment[6]
  int **gimg;           // periodic image (integers) of each ghost relative to its owner
  int maxxo;
  // pass-1 geometry of the pairs of one automaton (pair_loop)
  struct PairPre {
    int jj, j, proj;
    double R0, R1, R2, Va0, Va1, Va2, Vb0, Vb1, Vb2, rsq, r, n0, n1, n2, idbar, eraw, sc, xn;
  };
  PairPre *pre;
  int maxpre;

  void allocate();
  void ensure_fix();
  void rebuild_cache();
  void image_shifts();
  void canonical_geometry(int a, int b, const int *jimg, bool i_is_a, double *R, double *Va,
                          double *Vb);
  int find_slot(int i, double jtag);
  int new_slot(int i, double jtag);
  int initial_link_kind(int i, tagint jtag, double rsq, double dbar, bool same_body);
  template <int DIM> void automaton_update(int i, bool advance, double iV);
  template <int DIM, bool ADV, bool UNI> void pair_loop(bool init_links, double *tally, double runi);
};

}    // namespace LAMMPS_NS

#endif
#endif
