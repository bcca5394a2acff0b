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
                    [batch yes|no] [fused yes|no] [prune yes|no]
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

  // (compute pair: links, cross links now, cross formed, cross broken, links broken, welds
  // formed, contacts, and the pairs the fused kernel evaluated -- a diagnostic of the step)
  enum { NTALLY = 8 };

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
  int *eimg;            // periodic image of the partner relative to its owner, packed (pack_image)
  bigint *cacheoff;     // offset of atom i's pairs (-1: none)
  int *ecount;          // number of atom i's pairs
  int *eown;            // the automaton that evaluates each entry (the lists hold the automata's
                        // entries one after another, in ilist's order)
  bigint nentries;      // entries of the evaluation lists
  int ncached;          // local atoms when the lists were built
  int mirrors_pending;  // 1: the partners' copies of local pairs are behind (sync_mirrors)
  // the live pair states between two list rebuilds: one slot (fix mca/state's layout)
  // per entry of the evaluation lists, in their order, filled from the automata's slot
  // rows at each rebuild and written back to them before anything else reads the rows
  // (sync_mirrors).  The pair loop then reads and writes one dense stream in its own order
  // instead of slots spread over rows of maxpartner slots
  // (an entry holds a slot without its partner tag, which the step never reads: NP doubles;
  // the slot's index k is entry[k - 1], so that the slot layout's names apply.  psc points one
  // double past the allocation's start, pscbase, for the first entry's index -1)
  enum { NP = 11 };
  double *psc, *pscbase;
  bigint maxpsc;
  int psc_pending;      // 1: psc is ahead of the slot rows
  bigint maxflat;
  // one row per local automaton of what its pairs add up: force, torque, the Love-Weber sums
  // (xx yy zz xy xz yz) and the link counts, added to atom->f and torque after the pair loop.
  // The order puts everything a 2D pair adds in the first cache line (fx fy tz, L xx yy xy, the
  // two counts), so that a partner's sums cost one line (2D) or two (3D) instead of the three
  // or four of separate force, torque and sum arrays
  enum { C_F0 = 0, C_F1 = 1, C_T2 = 2, C_L0 = 3, C_L1 = 4, C_L3 = 5, C_NL = 6, C_NC = 7,
         C_F2 = 8, C_T0 = 9, C_T1 = 10, C_L2 = 11, C_L4 = 12, C_L5 = 13, SR = 16 };
  double **sacc;
  int maxsacc;
  bool sacc_dirty;    // a step's sums were not cleared (it did not finish): clear them all
  int coeffset;
  // one row per local and ghost atom: the owner's x, v, omega, the mean-stress term X and the
  // pending plastic strain increment (xx yy zz xy xz yz); PR doubles = two cache lines
  enum { R_X = 0, R_V = 3, R_OM = 6, R_XM = 9, R_DEP = 10, PR = 16 };
  double **xo;
  int **gimg;           // periodic image (integers) of each ghost relative to its owner
  int maxxo;
  // pair geometry and inputs of the general path (pass 2b of pair_loop)
  struct PairPre {
    int i, jj, j, proj;
    double R0, R1, R2, dV0, dV1, dV2, rsq, r, n0, n1, n2, idbar, eraw, sc, xn;    // dV: V_b - V_a
  };
  // A batch of pairs, one array per quantity (pair_loop: pass 1 fills it for a run of automata,
  // pass 2a computes the common case of all its pairs in vectorised loops, pass 2b applies the
  // pairs in order).  NBATCH pairs at most: the batch's arrays stay in the L1 cache.
  enum { NBATCH = 24, NBCAP = NBATCH };
  struct Batch {
    int i[NBCAP], jj[NBCAP], j[NBCAP], ef[NBCAP];
    bigint e[NBCAP], soff[NBCAP];    // entry of the evaluation lists, offset of i's slot (k >= 0)
    // pass 1: geometry
    // (dV = V_b - V_a: the law reads the velocities only as this difference)
    double R0[NBCAP], R1[NBCAP], R2[NBCAP], dV0[NBCAP], dV1[NBCAP], dV2[NBCAP], rsq[NBCAP],
        r[NBCAP], n0[NBCAP], n1[NBCAP], n2[NBCAP], idbar[NBCAP], eraw[NBCAP], proj[NBCAP],
        sc[NBCAP], xn[NBCAP], hasxi[NBCAP];
    // pass 1: state and partner inputs of the common case (kind FREE: not the common case)
    double kind[NBCAP], pn[NBCAP], cd[NBCAP], cr[NBCAP], xi0[NBCAP], xi1[NBCAP], xi2[NBCAP],
        rp0[NBCAP], rp1[NBCAP], rp2[NBCAP], th0[NBCAP], th1[NBCAP], th2[NBCAP], oa0[NBCAP],
        oa1[NBCAP], oa2[NBCAP], ob0[NBCAP], ob1[NBCAP], ob2[NBCAP], Xbar[NBCAP], D0[NBCAP],
        D1[NBCAP], D2[NBCAP], D3[NBCAP], D4[NBCAP], D5[NBCAP], ra[NBCAP], rb[NBCAP], dbar[NBCAP];
    // pass 2a: results of the common case
    double elig[NBCAP], xi0n[NBCAP], xi1n[NBCAP], xi2n[NBCAP], pnn[NBCAP], th0n[NBCAP],
        th1n[NBCAP], th2n[NBCAP], Fe0[NBCAP], Fe1[NBCAP], Fe2[NBCAP], Fd0[NBCAP], Fd1[NBCAP],
        Fd2[NBCAP], Ma0[NBCAP], Ma1[NBCAP], Ma2[NBCAP], ia[NBCAP], F0[NBCAP], F1[NBCAP],
        F2[NBCAP], nxF0[NBCAP], nxF1[NBCAP], nxF2[NBCAP], L0[NBCAP], L1[NBCAP], L2[NBCAP],
        L3[NBCAP], L4[NBCAP], L5[NBCAP], Fs0[NBCAP], Fs1[NBCAP], Fs2[NBCAP], Ms0[NBCAP],
        Ms1[NBCAP], Ms2[NBCAP];
    // (D3 false: the z components were not stored, and are +0 in 2D)
    template <bool D3> void get(int p, PairPre &P) const
    {
      P.i = i[p];
      P.jj = jj[p];
      P.j = j[p];
      P.proj = proj[p] != 0.0;
      P.R0 = R0[p];
      P.R1 = R1[p];
      P.R2 = D3 ? R2[p] : 0.0;
      P.dV0 = dV0[p];
      P.dV1 = dV1[p];
      P.dV2 = D3 ? dV2[p] : 0.0;
      P.rsq = rsq[p];
      P.r = r[p];
      P.n0 = n0[p];
      P.n1 = n1[p];
      P.n2 = n2[p];
      P.idbar = idbar[p];
      P.eraw = eraw[p];
      P.sc = sc[p];
      P.xn = xn[p];
    }
  };
  Batch *bat;
  // a batch of automata for the stress update (automata_update): inputs and results by component
  enum { NABATCH = 32 };
  struct AutomBatch {
    double acc[6][NABATCH], iV[NABATCH], ept2[NABATCH], ep[NABATCH], X[NABATCH], dg[NABATCH],
        seq[NABATCH], dep[6][NABATCH], sig[6][NABATCH];
  };
  AutomBatch *abat;
  double mass_uni;      // the mass of every automaton (compute), or 0 if they differ
  int maxecount;        // the largest number of pairs of one automaton (rebuild_cache)
  int batch_on;         // 1: pass 2a computes the common case (pair_style keyword batch)
  int fused_on;         // 1: pair_loop's fused kernel takes the common case (keyword fused)
  int prune_on;         // 1: the evaluation lists leave out pairs that cannot touch (prune)
  int ghost_rows_read;  // 1: some rank's evaluation lists read a ghost's row (rebuild_cache)

  void allocate();
  void ensure_fix();
  void rebuild_cache();
  void order_slots();
  int *sperm;           // order_slots: new slot index of each automaton's old ones
  bigint maxsperm;
  void image_shifts();
  // a lattice vector of periodic images (components |n| < 512) in one int
  static int pack_image(const int *n)
  {
    return (n[0] + 512) | (n[1] + 512) << 10 | (n[2] + 512) << 20;
  }
  static void unpack_image(int p, int *n)
  {
    n[0] = (p & 1023) - 512;
    n[1] = ((p >> 10) & 1023) - 512;
    n[2] = ((p >> 20) & 1023) - 512;
  }
  int find_slot(int i, double jtag);
  int new_slot(int i, double jtag);
  int initial_link_kind(int i, tagint jtag, double rsq, double dbar, bool same_body);
  template <int DIM>
  void automata_update(int i0, int na, bool advance, bool restore, double iVuni, double *sums);
  template <int DIM, bool ADV, bool UNI> void pair_loop(bool init_links, double *tally, double runi);
  template <int DIM, bool UNI> void batch_common(int n, double runi);
  template <int DIM, bool UNI> void batch_geometry(int n, double runi);
  // the fused kernel of pair_loop: its constants, and what it reads and returns of the loop's
  // state (cursor, virial, tallies)
  struct FusedCtx {
    int npre;
    const double *h, *hr;
    bool vremap, vglobal;
    double dt, G2, alpha, runi, dbar_u, idbar_u, A_u, kr_u, cd_u, cr_u, s_link, s_weld;
  };
  struct FusedIO {
    bigint e;    // the first of the four entries; on success, the entry after them
    int skip;    // not taken: the pairs to stage before the kernel is tried again (>= 1)
    bool local;
    double links, cross, vir[6];
  };
  template <int DIM> __attribute__((noinline)) int fused4(const FusedCtx &C, FusedIO &io);
};

}    // namespace LAMMPS_NS

#endif
#endif
