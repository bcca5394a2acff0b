/* ---------------------------------------------------------------------
   tribolmp MCA plugin: pair style mca (see pair_mca.h and mca_law.h)

   Step of the law, for every local automaton i and every neighbour j of a
   FULL neighbour list (a pair with a ghost partner is evaluated on the ranks
   of both partners, a pair of two local automata once for both; always in
   the canonical orientation a = smaller ID, b = larger ID, so both copies of
   the pair state evolve identically and no reverse communication is
   needed):
     1. ghosts receive X (mean stress term) and the pending plastic strain
        increment of their automaton (forward communication);
     2. the pair state (plastic offsets, tangential displacement, relative
        rotation) is advanced, links break, contacts weld;
     3. pair forces and torques are applied to i, the elastic pair forces are
        summed into i's Love-Weber stress;
     4. each automaton's stress is returned to the von Mises yield surface and
        the increment of plastic strain becomes pending for the next step.
   State updates happen once per timestep: the force evaluations of a run's
   setup (after read_restart, or of a second run command) do not advance the
   state and return the forces of the last committed step, so a restarted run
   continues the uninterrupted one.
------------------------------------------------------------------------- */

#include "pair_mca.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_mca_state.h"
#include "mca_memory.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstdint>
#include <cstring>

// the fused kernel of pair_loop needs AVX; without it every pair takes the batched path
// (same numbers: both are the general path's expressions in its order)
#if defined(__AVX__)
#include <immintrin.h>
#define MCA_FUSED 1
#else
#define MCA_FUSED 0
#endif

using namespace LAMMPS_NS;
using namespace MCALaw;

using FS = FixMCAState;

#if MCA_FUSED
namespace {
// four pairs, one per lane (+ - * / lane by lane).  Not __m256d, which may alias anything:
// GCC then kept the transposes' results in memory
typedef double V4 __attribute__((vector_size(32)));
inline V4 vb(double x) { return _mm256_set1_pd(x); }
inline V4 vsel(V4 m, V4 t, V4 f) { return _mm256_blendv_pd(f, t, m); }    // m ? t : f
inline V4 vlt(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }    // a < b (C++'s)
inline V4 vgt(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }    // a > b
inline V4 vne(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_NEQ_UQ); }   // a != b
inline V4 veq(V4 a, V4 b) { return _mm256_cmp_pd(a, b, _CMP_EQ_OQ); }    // a == b
inline V4 vabs(V4 a) { return _mm256_andnot_pd(vb(-0.0), a); }
// four rows of four <-> four columns, in registers
inline void transpose4(V4 &a, V4 &b, V4 &c, V4 &d)
{
  const V4 t0 = _mm256_unpacklo_pd(a, b), t1 = _mm256_unpackhi_pd(a, b);
  const V4 t2 = _mm256_unpacklo_pd(c, d), t3 = _mm256_unpackhi_pd(c, d);
  a = _mm256_permute2f128_pd(t0, t2, 0x20);
  b = _mm256_permute2f128_pd(t1, t3, 0x20);
  c = _mm256_permute2f128_pd(t0, t2, 0x31);
  d = _mm256_permute2f128_pd(t1, t3, 0x31);
}
// the last three values of a pair state entry (one more would read the next entry, or past the
// end of psc)
inline V4 load3(const double *p)
{
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p)), _mm_load_sd(p + 2), 1);
}
inline void store3(double *p, V4 v)
{
  _mm_storeu_pd(p, _mm256_castpd256_pd128(v));
  _mm_store_sd(p + 2, _mm256_extractf128_pd(v, 1));
}
}    // namespace
#endif
// (psc entries leave out the tag, the first value of a slot: pair_mca.h)
static_assert(FixMCAState::S_TAG == 0, "psc entries hold a slot without its first value");

PairMCA::PairMCA(LAMMPS *lmp) :
    Pair(lmp), link_init(1), attach_type(0), link_tol(0.05), cutfac(1.25), maxrad(0.0), fix(nullptr),
    cache(nullptr), ncache(nullptr), maxcache_atoms(0), coeffset(0)
{
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 1;
  manybody_flag = 1;
  no_virial_fdotr_compute = 1;
  finitecutflag = 1;
  comm_forward = PR;
  nextra = NTALLY;
  pvector = new double[NTALLY];
  for (int k = 0; k < NTALLY; k++) pvector[k] = 0.0;
  cacheflat = nullptr;
  mirrorflat = nullptr;
  eimg = nullptr;
  cacheoff = nullptr;
  ecount = nullptr;
  eown = nullptr;
  nentries = 0;
  ej = nullptr;
  eflag = nullptr;
  ncached = 0;
  mirrors_pending = 0;
  psc = pscbase = nullptr;
  maxpsc = 0;
  psc_pending = 0;
  maxflat = 0;
  sacc = nullptr;
  maxsacc = 0;
  sacc_dirty = false;
  xo = nullptr;
  gimg = nullptr;
  maxxo = 0;
  bat = nullptr;
  abat = nullptr;
  maxecount = 0;
  mass_uni = 0.0;
  batch_on = 1;
  fused_on = 1;
  prune_on = 1;
  ghost_rows_read = 1;
  sperm = nullptr;
  maxsperm = 0;
}

PairMCA::~PairMCA()
{
  delete[] pvector;
  memory->destroy(cacheflat);
  memory->destroy(mirrorflat);
  memory->destroy(eimg);
  memory->destroy(pscbase);
  memory->destroy(cacheoff);
  memory->destroy(ecount);
  memory->destroy(ej);
  memory->destroy(eflag);
  memory->destroy(eown);
  memory->destroy(sacc);
  memory->destroy(xo);
  memory->destroy(gimg);
  memory->destroy(sperm);
  delete bat;
  delete abat;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

void PairMCA::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = 0;
}

void PairMCA::settings(int narg, char **arg)
{
  int iarg = 0;
  while (iarg < narg) {
    if (iarg + 2 > narg) error->all(FLERR, "pair_style mca: keyword {} needs a value", arg[iarg]);
    if (strcmp(arg[iarg], "link_init") == 0) {
      if (strcmp(arg[iarg + 1], "none") == 0) link_init = 0;
      else if (strcmp(arg[iarg + 1], "same") == 0) link_init = 1;
      else if (strcmp(arg[iarg + 1], "all") == 0) link_init = 2;
      else if (strcmp(arg[iarg + 1], "bonds") == 0) link_init = 3;
      else error->all(FLERR, "pair_style mca: link_init: expected none|same|all|bonds, got {}", arg[iarg + 1]);
    } else if (strcmp(arg[iarg], "attach_type") == 0) {
      attach_type = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "link_tol") == 0) {
      link_tol = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (link_tol < 0.0 || link_tol > 0.2)
        error->all(FLERR, "pair_style mca: link_tol: expected 0-0.2, got {}", link_tol);
    } else if (strcmp(arg[iarg], "batch") == 0) {
      // (the vectorised common case of pair_loop; 'no' runs every pair on the general path,
      // same numbers, for the test that the two agree)
      batch_on = utils::logical(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "fused") == 0) {
      // (the fused kernel of the common case; 'no' leaves it to the batch, same numbers,
      // for the test that the two agree and for timing)
      fused_on = utils::logical(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "prune") == 0) {
      // (rebuild_cache leaves out pairs without state beyond contact plus skin; 'no' keeps
      // every neighbour, same numbers, for the test that pruning loses no contact)
      prune_on = utils::logical(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "cutoff") == 0) {
      cutfac = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (cutfac < 1.05 || cutfac > 3.0)
        error->all(FLERR, "pair_style mca: cutoff: expected 1.05-3 (x max diameter), got {}", cutfac);
    } else
      error->all(FLERR, "pair_style mca: unknown keyword {}", arg[iarg]);
    iarg += 2;
  }
}

void PairMCA::coeff(int narg, char **arg)
{
  if (narg != 12)
    error->all(FLERR, "pair_coeff mca: expected '* * G nu sigma_y sigma_0 H mu eta weld_factor "
               "weld_onset damp' (12 words), got {}", narg);
  if (strcmp(arg[0], "*") != 0 || strcmp(arg[1], "*") != 0)
    error->all(FLERR, "pair_coeff mca: one material only: expected 'pair_coeff * * ...', got {} {}",
               arg[0], arg[1]);
  if (!allocated) allocate();
  const char *names[10] = {"G", "nu", "sigma_y", "sigma_0", "H", "mu", "eta", "weld_factor",
                           "weld_onset", "damp"};
  double v[10];
  for (int k = 0; k < 10; k++) v[k] = utils::numeric(FLERR, arg[k + 2], false, lmp);
  mat.dim = domain->dimension;
  mat.G = v[0]; mat.nu = v[1]; mat.sy = v[2]; mat.s0 = v[3]; mat.H = v[4];
  mat.mu = v[5]; mat.eta = v[6]; mat.wfac = v[7]; mat.wonset = v[8]; mat.damp = v[9];
  if (!(mat.G > 0.0)) error->all(FLERR, "pair_coeff mca: {}: expected > 0, got {}", names[0], v[0]);
  // the lagged mean-stress term converges for |alpha| < 1
  const double nulo = (mat.dim == 3) ? -0.25 : -0.5;
  if (!(mat.nu > nulo && mat.nu < 0.5))
    error->all(FLERR, "pair_coeff mca: nu: expected in ({}, 0.5) in {}D, got {}", nulo, mat.dim, v[1]);
  if (!(mat.sy > 0.0)) error->all(FLERR, "pair_coeff mca: sigma_y: expected > 0, got {}", v[2]);
  if (!(mat.s0 >= mat.sy))
    error->all(FLERR, "pair_coeff mca: sigma_0: expected >= sigma_y {}, got {}", mat.sy, v[3]);
  if (!(mat.H >= 0.0)) error->all(FLERR, "pair_coeff mca: H: expected >= 0, got {}", v[4]);
  if (!(mat.mu >= 0.0)) error->all(FLERR, "pair_coeff mca: mu: expected >= 0, got {}", v[5]);
  if (!(mat.eta >= 0.0)) error->all(FLERR, "pair_coeff mca: eta: expected >= 0, got {}", v[6]);
  if (!(mat.wfac >= 0.0 && mat.wfac <= 1.0))
    error->all(FLERR, "pair_coeff mca: weld_factor: expected 0-1, got {}", v[7]);
  if (!(mat.wonset >= 0.0)) error->all(FLERR, "pair_coeff mca: weld_onset: expected >= 0, got {}", v[8]);
  if (!(mat.damp >= 0.0 && mat.damp <= 1.0))
    error->all(FLERR, "pair_coeff mca: damp: expected 0-1, got {}", v[9]);
  mat.derive();
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 1;
  coeffset = 1;
  ensure_fix();
}

void PairMCA::ensure_fix()
{
  Fix *f = modify->get_fix_by_id("mca_state");
  if (!f) f = modify->add_fix("mca_state all mca/state");
  fix = dynamic_cast<FixMCAState *>(f);
  if (!fix) error->all(FLERR, "pair mca: fix ID mca_state exists but is not fix mca/state");
}

void PairMCA::init_style()
{
  if (!atom->radius_flag || !atom->omega_flag || !atom->torque_flag || !atom->rmass_flag)
    error->all(FLERR, "pair mca: needs per-atom radius, omega, torque and mass "
               "(atom_style bpm/sphere or sphere)");
  // (no ghost velocities needed: the rows of xo carry each automaton's v and omega to its ghosts)
  if (!coeffset) error->all(FLERR, "pair mca: pair_coeff * * ... not set");
  if (link_init == 3 && (!atom->molecular || force->newton_bond))
    error->all(FLERR, "pair mca: link_init bonds needs a molecular atom style and 'newton on off' "
               "(every atom must hold its own bonds)");
  mat.dim = domain->dimension;
  mat.derive();
  neighbor->add_request(this, NeighConst::REQ_FULL);
  ensure_fix();
  double mr = 0.0;
  for (int i = 0; i < atom->nlocal; i++) mr = (atom->radius[i] > mr) ? atom->radius[i] : mr;
  MPI_Allreduce(&mr, &maxrad, 1, MPI_DOUBLE, MPI_MAX, world);
  if (maxrad <= 0.0) error->all(FLERR, "pair mca: all automata have zero radius");
}

double PairMCA::init_one(int i, int j)
{
  if (setflag[i][j] == 0) error->all(FLERR, "pair mca: coefficients for types {} {} not set", i, j);
  return cutfac * 2.0 * maxrad;
}

/* ----------------------------------------------------------------------
   slots of the neighbour list: after each rebuild every neighbour of each
   local atom is mapped to its slot (or -1); partners that left the list are
   dropped (a link that left the neighbour list counts as broken)
------------------------------------------------------------------------- */

int PairMCA::find_slot(int i, double jtag)
{
  for (int k = 0; k < fix->maxpartner; k++)
    if (fix->slots[i][k * FS::NSLOT + FS::S_TAG] == jtag) return k;
  return -1;
}

int PairMCA::new_slot(int i, double jtag)
{
  for (int k = 0; k < fix->maxpartner; k++) {
    double *s = fix->slot(i, k);
    if (s[FS::S_TAG] == 0.0) {
      memset(s, 0, sizeof(double) * FS::NSLOT);
      s[FS::S_TAG] = jtag;
      return k;
    }
  }
  error->one(FLERR, "pair mca: automaton {} has more than {} linked or touching partners; "
             "declare 'fix mca_state all mca/state maxpartner N' with a larger N",
             atom->tag[i], fix->maxpartner);
  return -1;
}

/* kind of the initial link between local atom i and partner jtag (FREE: none).
   same/all: every pair closer than (1 + link_tol) dbar (same: of the same molecule);
   bonds: the pairs the data file bonds, bond type attach_type as an unbreakable attachment */

int PairMCA::initial_link_kind(int i, tagint jtag, double rsq, double dbar, bool same_body)
{
  if (link_init == 3) {
    for (int m = 0; m < atom->num_bond[i]; m++)
      if (atom->bond_atom[i][m] == jtag)
        return (atom->bond_type[i][m] == attach_type) ? FS::ATTACH : FS::LINK;
    return FS::FREE;
  }
  const double lim = (1.0 + link_tol) * dbar;
  if (rsq < lim * lim && (link_init == 2 || same_body)) return FS::LINK;
  return FS::FREE;
}

void PairMCA::rebuild_cache()
{
  const int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh, **firstneigh = list->firstneigh;
  const int nlocal = atom->nlocal;
  tagint *tag = atom->tag;
  tagint *mol = atom->molecule_flag ? atom->molecule : nullptr;
  if (atom->nmax > maxcache_atoms) {
    maxcache_atoms = atom->nmax;
    memory->destroy(cacheoff);
    memory->destroy(ecount);
    memory->create(cacheoff, maxcache_atoms, "pair:mca:cacheoff");
    memory->create(ecount, maxcache_atoms, "pair:mca:ecount");
  }
  bigint total = 0;
  for (int ii = 0; ii < inum; ii++) total += numneigh[ilist[ii]];
  if (total > maxflat) {
    maxflat = total + total / 4 + 16;
    memory->destroy(ej);
    memory->destroy(eflag);
    memory->destroy(cacheflat);
    memory->destroy(mirrorflat);
    memory->destroy(eimg);
    memory->destroy(eown);
    memory->create(ej, maxflat, "pair:mca:ej");
    // (three entries more: the fused kernel reads the lists' ints four entries at a time)
    memory->create(eown, maxflat + 3, "pair:mca:eown");
    memory->create(eimg, maxflat, "pair:mca:eimg");
    memory->create(eflag, maxflat, "pair:mca:eflag");
    memory->create(cacheflat, maxflat, "pair:mca:cacheflat");
    memory->create(mirrorflat, maxflat, "pair:mca:mirrorflat");
  }
  const int mp = fix->maxpartner;
  int *seen = new int[mp];
  // Pruned lists: a pair without state is left out when it is farther apart than its contact
  // distance plus the skin.  Safe only when LAMMPS rebuilds the lists as soon as any automaton
  // (or, with a changing box, the box corners plus an automaton) has moved half the skin
  // (check yes, every 1, delay 0): between two rebuilds a pair's distance then changes by at
  // most the skin, so a pruned pair cannot touch before the next rebuild.  The relative margin
  // 1e-9 covers the rounding of a ghost's coordinates (owner + box vector) against the owner
  // rank's.  Not on the first step when initial links are made (link_tol reaches beyond
  // contact).  The neighbour cutoff (cutfac x diameter + skin) still bounds where a linked or
  // welded pair is seen; pruning drops, e.g., the second FCC shell at sqrt(2) d, a third of
  // the pairs a 3D lattice evaluates.
  const bool prune = prune_on && neighbor->dist_check && neighbor->every == 1 &&
      neighbor->delay == 0 && !neighbor->build_once && !(link_init && !fix->initialized);
  double **x = atom->x;
  const double *radius = atom->radius;
  const double skin = neighbor->skin;
  // (the map from IDs to local indices exists for molecular atom styles, and LAMMPS sets it at
  // every reneighbouring, before the lists are built; a local atom takes precedence over its
  // ghost images)
  const bool usemap = atom->map_style != Atom::MAP_NONE;
  bigint off = 0;
  for (int i = 0; i < nlocal; i++) {
    cacheoff[i] = -1;
    ecount[i] = 0;
  }
  maxecount = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double itag = (double) tag[i];
    cacheoff[i] = off;
    for (int k = 0; k < mp; k++) seen[k] = 0;
    int *jlist = firstneigh[i];
    int ne = 0;
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double jtag = (double) tag[j];
      const int k = find_slot(i, jtag);
      if (k >= 0) {
        if (seen[k])
          error->one(FLERR, "pair mca: automata {} and {} see each other twice; the periodic box "
                     "must be longer than twice the pair cutoff", tag[i], tag[j]);
        seen[k] = 1;
      }
      // the pairs this automaton evaluates, in the neighbour list's order: every ghost partner
      // (but its own image), and a local partner with the larger ID (evaluated here for both).
      // A ghost that is a periodic image of a local automaton is that automaton: the pair is
      // evaluated once, by the smaller ID, as a local pair with the image's lattice vector
      // (ej is then the owner).  A pair across a periodic boundary of the rank otherwise costs
      // two evaluations (a tenth of the pairs of the thin 3D friction slab)
      if (jtag == itag) continue;
      const int *jimg = gimg[j];
      const bool image = (jimg[0] | jimg[1] | jimg[2]) != 0;
      int jo = j;    // the partner's own index (local or ghost)
      if (j >= nlocal && image && usemap) {
        const int m = atom->map(tag[j]);
        if (m >= 0 && m < nlocal) jo = m;
      }
      const bool jlocal = jo < nlocal;
      if (jlocal && jtag < itag) continue;
      // local partner: its slot for this automaton
      const int kj = jlocal ? find_slot(jo, itag) : -1;
      if (prune && k < 0 && kj < 0) {
        // no state on either side: the pair matters only if it can touch before the next
        // rebuild, and by then its distance has changed by at most the skin
        const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
        const double lim = (radius[i] + radius[j] + skin) * (1.0 + 1e-9);
        if (dx * dx + dy * dy + dz * dz >= lim * lim) continue;
      }
      const int e = off + ne++;
      eown[e] = i;
      ej[e] = jo;
      eflag[e] = (itag < jtag ? E_IA : 0) | (jlocal ? E_LOCAL : 0) | (image ? E_IMAGE : 0) |
          ((!mol || mol[i] == mol[j]) ? E_SAME : 0);
      eimg[e] = image ? pack_image(jimg) : 0;
      cacheflat[e] = k;
      mirrorflat[e] = kj;
    }
    ecount[i] = ne;
    off += ne;
    if (ne > maxecount) maxecount = ne;
    for (int k = 0; k < mp; k++) {
      double *s = fix->slot(i, k);
      if (s[FS::S_TAG] == 0.0 || seen[k]) continue;
      const int kind = static_cast<int>(s[FS::S_KIND]);
      if ((kind == FS::LINK || kind == FS::WELD) && (double) tag[i] < s[FS::S_TAG])
        fix->autom[i][FS::A_LB] += 1.0;
      memset(s, 0, sizeof(double) * FS::NSLOT);
    }
  }
  delete[] seen;
  nentries = off;
  // does any pair read a ghost's row until the next rebuild?  (one answer for all ranks: the
  // forward communication is collective)
  int ghost_local = 0;
  for (bigint e = 0; e < off && !ghost_local; e++)
    if (!(eflag[e] & E_LOCAL)) ghost_local = 1;
  MPI_Allreduce(&ghost_local, &ghost_rows_read, 1, MPI_INT, MPI_MAX, world);
  ncached = nlocal;
  mirrors_pending = 0;
  order_slots();
  // the pair states of the lists' entries into their dense copy (psc), in the lists' order
  // (allocated even for empty lists, so that psc is never a null pointer the loop offsets)
  if (!pscbase || off * NP > maxpsc) {
    maxpsc = maxflat * NP;
    memory->destroy(pscbase);
    memory->create(pscbase, maxpsc + 1, "pair:mca:psc");
    MCAMemory::hugepage_hint(pscbase, sizeof(double) * (maxpsc + 1));
    psc = pscbase + 1;
  }
  for (int i = 0; i < nlocal; i++) {
    const bigint eoff = cacheoff[i];
    if (eoff < 0) continue;
    for (bigint e = eoff; e < eoff + ecount[i]; e++) {
      double *d = psc + e * NP;
      if (cacheflat[e] >= 0) memcpy(d, fix->slot(i, cacheflat[e]) + 1, sizeof(double) * NP);
      else memset(d, 0, sizeof(double) * NP);
    }
  }
  psc_pending = 0;
}

/* Each automaton's slots in the order its evaluation list reads them, the slots of the pairs it
   evaluates first, then those it holds as the partner's copy (mirrors), then the free ones.
   The copies between the rows and psc (rebuild_cache, sync_mirrors) then read and write one
   contiguous run of each automaton's row instead of slots scattered over the whole row (20
   slots of 96 bytes per automaton in 3D); between two rebuilds the step reads only psc.  Only
   the slot indices change: the sums are formed in the order of the evaluation lists, and a
   slot is found by its partner's tag, so no number changes (tests/mca/test_law_batch.py,
   test_law_parallel.py).  Called at the end of rebuild_cache, when the mirror copies are
   current (sync_mirrors ran before) and the lists hold every slot index in use. */

void PairMCA::order_slots()
{
  const int mp = fix->maxpartner, nlocal = atom->nlocal;
  if ((bigint) nlocal * mp > maxsperm) {
    maxsperm = (bigint) atom->nmax * mp;
    memory->destroy(sperm);
    memory->create(sperm, maxsperm, "pair:mca:sperm");
  }
  double *tmp = new double[mp * FS::NSLOT];
  for (int i = 0; i < nlocal; i++) {
    int *perm = sperm + (bigint) i * mp;    // old slot index -> new
    for (int k = 0; k < mp; k++) perm[k] = -1;
    int nk = 0;
    const bigint eoff = cacheoff[i];
    const int ne = (eoff >= 0) ? ecount[i] : 0;
    for (int e = 0; e < ne; e++) {
      const int k = cacheflat[eoff + e];
      if (k >= 0 && perm[k] < 0) perm[k] = nk++;
    }
    double *row = fix->slots[i];
    for (int k = 0; k < mp; k++)
      if (perm[k] < 0 && row[k * FS::NSLOT + FS::S_TAG] != 0.0) perm[k] = nk++;
    bool same = true;
    for (int k = 0; k < mp; k++) {
      if (perm[k] < 0) perm[k] = nk++;
      same = same && perm[k] == k;
    }
    if (same) continue;
    memcpy(tmp, row, sizeof(double) * mp * FS::NSLOT);
    for (int k = 0; k < mp; k++)
      memcpy(row + perm[k] * FS::NSLOT, tmp + k * FS::NSLOT, sizeof(double) * FS::NSLOT);
    for (int e = 0; e < ne; e++) {
      int &k = cacheflat[eoff + e];
      if (k >= 0) k = perm[k];
    }
  }
  delete[] tmp;
  // the partners' slot indices of local pairs, into the partners' new order
  for (int i = 0; i < nlocal; i++) {
    const bigint eoff = cacheoff[i];
    if (eoff < 0) continue;
    for (int e = 0; e < ecount[i]; e++) {
      int &kj = mirrorflat[eoff + e];
      if (kj >= 0) kj = sperm[(bigint) ej[eoff + e] * mp + kj];
    }
  }
}

/* pending copies (fix_mca_state.h), called before anything but the pair loop reads the slot
   rows (atoms move in the arrays, a restart is written, the lists are rebuilt): the live
   states of psc go back to the evaluating automata's rows, and a pair of two local automata,
   evaluated on the copy of the one with the smaller ID, to j's copy as well (i's with the
   partner tag of j).  The pairs with a pending mirror copy are those of the evaluation lists
   that hold a state on both sides.  Leaving out the write-back of psc fails the restart, MPI
   and momentum tests of tests/mca/test_law_parallel.py. */

void PairMCA::sync_mirrors()
{
  if ((!mirrors_pending && !psc_pending) || cacheoff == nullptr) return;
  const bool mirrors = mirrors_pending, own = psc_pending;
  mirrors_pending = 0;
  psc_pending = 0;
  tagint *tag = atom->tag;
  // (the atoms of the last rebuild: an atom added since has no list)
  for (int i = 0; i < ncached; i++) {
    const bigint off = cacheoff[i];
    if (off < 0) continue;
    for (bigint e = off; e < off + ecount[i]; e++) {
      if (cacheflat[e] < 0) continue;
      // (the live state, all but the tag: the row's slot keeps its partner's)
      const double *src = psc + e * NP;
      if (own) memcpy(fix->slot(i, cacheflat[e]) + 1, src, sizeof(double) * NP);
      if (!mirrors || !(eflag[e] & E_LOCAL) || mirrorflat[e] < 0) continue;
      double *sj = fix->slot(ej[e], mirrorflat[e]);
      memcpy(sj + 1, src, sizeof(double) * NP);
      sj[FS::S_TAG] = (double) tag[i];
    }
  }
}

/* ----------------------------------------------------------------------
   periodic images.  A pair with a ghost partner is evaluated on the ranks of
   both partners, and both copies of its state must evolve bit for bit alike
   (a link that breaks on one rank only would leave a one-sided state).  A
   ghost that is a periodic image holds x_owner + shift, rounded, so x_b - x_a
   differs in the last bits between the two ranks.  Each ghost's image is
   therefore kept as integers (fixed between reneighbourings), and the pair's
   geometry is computed from the owners' coordinates plus the integer lattice
   vector, with the same operations on every rank.
------------------------------------------------------------------------- */

void PairMCA::image_shifts()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **x = atom->x;
  const double *hi = domain->h_inv;
  for (int i = 0; i < nlocal; i++) gimg[i][0] = gimg[i][1] = gimg[i][2] = 0;
  for (int i = nlocal; i < nall; i++) {
    const double d[3] = {x[i][0] - xo[i][0], x[i][1] - xo[i][1], x[i][2] - xo[i][2]};
    if (domain->triclinic) {
      gimg[i][0] = static_cast<int>(std::lround(hi[0] * d[0] + hi[5] * d[1] + hi[4] * d[2]));
      gimg[i][1] = static_cast<int>(std::lround(hi[1] * d[1] + hi[3] * d[2]));
      gimg[i][2] = static_cast<int>(std::lround(hi[2] * d[2]));
    } else {
      gimg[i][0] = static_cast<int>(std::lround(d[0] / domain->xprd));
      gimg[i][1] = static_cast<int>(std::lround(d[1] / domain->yprd));
      gimg[i][2] = static_cast<int>(std::lround(d[2] / domain->zprd));
    }
  }
}


/* ---------------------------------------------------------------------- */

void PairMCA::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  if (!fix) ensure_fix();

  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const int nlocal = atom->nlocal;
  const int dim = domain->dimension;
  const bool advance = (double) update->ntimestep > fix->last_commit;
  const bool init_links = advance && !fix->initialized && link_init != 0;

  if (atom->nmax > maxxo) {
    maxxo = atom->nmax;
    memory->destroy(xo);
    memory->destroy(gimg);
    memory->create(xo, maxxo, PR, "pair:mca:xo");
    MCAMemory::hugepage_hint(xo[0], sizeof(double) * maxxo * PR);
    memory->create(gimg, maxxo, 3, "pair:mca:gimg");
  }
  // everything a pair reads of an automaton in one row of PR doubles (two cache lines; ghosts
  // receive it): position and velocity (the owner's), angular velocity, the mean-stress term X
  // (of the previous step; a re-evaluation uses the X the forces of the last committed step
  // used, so it reproduces those forces exactly) and the pending plastic strain increment.  A
  // partner then costs two cache lines where x, v, omega and the inputs cost four
  double **autom = fix->autom;
  const int ix = advance ? FS::A_X : FS::A_XU;
  if (nlocal > maxsacc) {
    maxsacc = atom->nmax;
    memory->destroy(sacc);
    memory->create(sacc, maxsacc, SR, "pair:mca:sacc");
    MCAMemory::hugepage_hint(sacc[0], sizeof(double) * maxsacc * SR);
    // (in 2D the second cache line of a row -- the z force, x and y torque, the zz, xz, yz
    // sums -- is never added to: cleared once here, not every step)
    memset(sacc[0], 0, sizeof(double) * maxsacc * SR);
    sacc_dirty = false;
  }
  // The Love-Weber sums are cleared where they are last read (automata_update, while their
  // rows are in the cache), not here: a pass over them before the pair loop brought every row in from
  // memory once more.  A step that did not reach that point (an error caught by the caller)
  // leaves them dirty: cleared here in one pass
  if (sacc_dirty) memset(sacc[0], 0, sizeof(double) * maxsacc * SR);
  sacc_dirty = true;
  for (int i = 0; i < nlocal; i++) {
    double *xoi = xo[i];
    const double *xi = x[i], *vi = v[i], *oi = omega[i], *am = autom[i];
    for (int c = 0; c < 3; c++) {
      xoi[R_X + c] = xi[c];
      xoi[R_V + c] = vi[c];
      xoi[R_OM + c] = oi[c];
    }
    xoi[R_XM] = am[ix];
    for (int c = 0; c < 6; c++) xoi[R_DEP + c] = am[FS::A_DEP + c];
  }
  // The ghosts' rows are read only by pairs with a ghost that is not a periodic image of a
  // local automaton (those are evaluated from the owner's row, rebuild_cache): on one rank
  // none, so between rebuilds their communication is skipped (2-3 % of a 3D friction step).
  // On a rebuild step they are sent: image_shifts reads them, and the new lists may need them
  const bool rebuild = neighbor->ago == 0 || cacheoff == nullptr;
  if (rebuild || ghost_rows_read) comm->forward_comm(this);
  if (rebuild) {
    // the mirror copies of the pair states must be current before the slots are re-mapped
    sync_mirrors();
    image_shifts();
    rebuild_cache();
  }


  // one radius for all automata (the common case): the pair constants are computed once
  const int nall = nlocal + atom->nghost;
  // (and one mass: one pair of link damping constants; both found in one pass)
  double runi = (nall > 0) ? atom->radius[0] : 0.0;
  mass_uni = (nall > 0) ? atom->rmass[0] : 0.0;
  for (int i = 1; i < nall && (runi > 0.0 || mass_uni > 0.0); i++) {
    if (atom->radius[i] != runi) runi = 0.0;
    if (atom->rmass[i] != mass_uni) mass_uni = 0.0;
  }
  double tally[4] = {0.0, 0.0, 0.0, 0.0};
  if (runi > 0.0) {
    if (dim == 2) {
      if (advance) pair_loop<2, true, true>(init_links, tally, runi);
      else pair_loop<2, false, true>(init_links, tally, runi);
    } else {
      if (advance) pair_loop<3, true, true>(init_links, tally, runi);
      else pair_loop<3, false, true>(init_links, tally, runi);
    }
  } else {
    if (dim == 2) {
      if (advance) pair_loop<2, true, false>(init_links, tally, 1.0);
      else pair_loop<2, false, false>(init_links, tally, 1.0);
    } else {
      if (advance) pair_loop<3, true, false>(init_links, tally, 1.0);
      else pair_loop<3, false, false>(init_links, tally, 1.0);
    }
  }
  const double tally_links = tally[0], tally_cross = tally[1], tally_contacts = tally[2];
  const double tally_fused = tally[3];

  // per automaton, in one pass over its state row: stress and plastic update, the tallies,
  // and the committed step's pair forces.  Those of a committed step are stored: a
  // re-evaluation of the same step (the setup of a run continued from a restart, or of a second
  // run command) returns them unchanged.  Recomputing them would use full-step velocities where
  // the committed step used half-step ones (velocity Verlet), so damping and viscosity would
  // differ by one step
  if (!abat) abat = new AutomBatch();
  const bool restore = !advance && fix->last_commit >= 0.0;
  // (the stress is the Love-Weber sum times 1/V)
  const double iVuni = (runi > 0.0) ? 1.0 / automaton_volume(2.0 * runi, dim) : 0.0;
  // (in batches of automata: the stress update of a batch in vectorised loops, automata_update)
  double sums[4] = {0.0, 0.0, 0.0, 0.0};    // (counters cf cb lb wf, in the automata's order)
  for (int i = 0; i < nlocal; i += NABATCH) {
    const int na = (nlocal - i < NABATCH) ? nlocal - i : NABATCH;
    if (dim == 2) automata_update<2>(i, na, advance, restore, iVuni, sums);
    else automata_update<3>(i, na, advance, restore, iVuni, sums);
  }
  const double cf = sums[0], cb = sums[1], lb = sums[2], wf = sums[3];
  sacc_dirty = false;
  if (init_links) fix->initialized = 1;
  if (advance) fix->last_commit = (double) update->ntimestep;

  pvector[0] = tally_links;
  pvector[1] = tally_cross;
  pvector[2] = cf;
  pvector[3] = cb;
  pvector[4] = lb;
  pvector[5] = wf;
  pvector[6] = tally_contacts;
  pvector[7] = tally_fused;
}

/* ----------------------------------------------------------------------
   the pair loop, specialised for the dimension and for a committed step
   (ADV: the pair state advances) or a re-evaluation.  In 2D every z
   component of positions, velocities, tangential displacements, forces and
   the x, y components of rotations are exactly zero (fix enforce2d), so the
   2D instance leaves them out: the same numbers as the general arithmetic
   (terms that are +-0 do not change a sum), with a third of the work.
   Small vectors are kept in scalars, not arrays, so that the compiler keeps
   them in registers.

   The pairs are evaluated in batches of NBATCH, in the order of the
   evaluation lists (rebuild_cache):
     pass 1a  gathers each pair's geometry, state and partner inputs into the
              batch's arrays (one array per quantity);
     pass 1b  distance, normal, raw strain and tangential rescaling of the
              whole batch (batch_geometry, vectorised: square roots and
              divisions of many pairs at once);
     pass 2a  the common case of the whole batch -- an existing link, weld or
              attachment advanced by one step that does not break -- in
              vectorised loops (batch_common);
     pass 2b  pair by pair in order: the common case writes its state back and
              applies its forces; every other pair (contacts, new links,
              ruptures, welds, the first step, re-evaluations) runs the general
              path below from its untouched state.
   Both paths are the same expressions in the same order, and the sums into
   forces, torques and stresses are formed pair by pair in the same order, so
   batching changes no number (tests/mca/test_law_batch.py: 'pair_style mca
   batch no' runs every pair on the general path).
------------------------------------------------------------------------- */

template <int DIM, bool ADV, bool UNI> void PairMCA::pair_loop(bool init_links, double *tally, double runi)
{
  constexpr bool D3 = (DIM == 3);
  const int inum = list->inum;
  if (inum == 0) return;
  // per-atom arrays through their contiguous storage (one load less per access than the
  // row pointers)
  double *radius = atom->radius, *rmass = atom->rmass;
  tagint *tag = atom->tag;
  const double dt = update->dt;
  double **autom = fix->autom;
  double *slots = fix->slots[0];
  const int slotrow = fix->maxpartner * FS::NSLOT;
  const double *xo0 = xo[0];
  double *sacc0 = sacc[0];
  const double *h = domain->h;
  const double *hr = domain->h_rate;
  const bool vremap = domain->deform_vremap;
  const double G2 = 2.0 * mat.G;
  const double alpha = mat.alpha;
  // UNI: all automata have the radius runi, so the pair constants are the same for every pair
  // (the same expressions, evaluated once)
  const double dbar_u = runi + runi;
  const double A_u = pair_area(dbar_u, DIM), kr_u = rotational_stiffness(mat, A_u, dbar_u);
  const double cv_u = viscous_factor(mat, A_u, dbar_u);
  // one radius and one mass for all automata: one pair of link damping constants
  const bool muni = UNI && mass_uni > 0.0;
  double cd_u = 0.0, cr_u = 0.0;
  if (muni) link_damping(mat, mass_uni, mass_uni, runi, runi, A_u, dbar_u, cd_u, cr_u);
  double tally_links = 0.0, tally_cross = 0.0, tally_contacts = 0.0, tally_fused = 0.0;

  int *ilist = list->ilist;
  bool any_mirror = false;
  // Virial: per-atom tallies (ev_tally_xyz_full, which also forms the global sums) only when
  // per-atom energy or virial is asked for; the global virial alone is summed inline.  A
  // 'fix ave/time 1 N N' of any compute makes LAMMPS ask for the global virial on every step
  // (the friction deck's), where the per-atom path's function calls cost a fifth of the loop
  const bool peratom = evflag && (eflag_atom || vflag_atom);
  const bool vglobal = vflag_global && !peratom;
  double vir[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

  // the batch of pairs (pass 1 fills it for a run of automata, pass 2a computes the common
  // case of all of them at once, pass 2b applies them in order)
  if (!bat) bat = new Batch();
  Batch &B = *bat;

  // a pair's force F (on a), signed force and moment Fs, Ms (on i), n x F and the Love-Weber
  // dyad L (xx yy zz xy xz yz) added to i and, when j is local, subtracted from j (F_b = -F_a,
  // M_b = -M_a; x - y is x + (-1) y exactly).  Both automata see the same n x F (n and F both
  // change sign) and the same n (x) F_e; the torque of the tangential force is r n x F
  auto scatter = [&](int i, int j, bool jlocal, bool i_is_a, bool cross, int kind, double R0,
                     double R1, double R2, const double *Fv, const double *Fsv, const double *Msv,
                     const double *nxF, const double *Lv) __attribute__((always_inline)) {
    const bool attached = (kind == FS::ATTACH);
    const bool linked = (kind == FS::LINK || kind == FS::WELD || attached);
    const bool counted = linked && !attached;    // attachments (to rigid layers) are not links
    const double sg = i_is_a ? 1.0 : -1.0;
    const double dx = sg * R0, dy = sg * R1, dz = sg * R2;
    auto apply = [&](int q, bool plus, double delx, double dely, double delz)
                     __attribute__((always_inline)) {
      const double rq = UNI ? runi : radius[q];
      // (force, torque and sums in q's row of sacc: added to atom->f, torque in compute)
      double *acc = sacc0 + SR * q;
      const double T2 = rq * nxF[2];
      if (plus) {
        acc[C_F0] += Fsv[0];
        acc[C_F1] += Fsv[1];
        acc[C_T2] += T2 + Msv[2];
      } else {
        acc[C_F0] -= Fsv[0];
        acc[C_F1] -= Fsv[1];
        acc[C_T2] += T2 - Msv[2];
      }
      acc[C_L0] += rq * Lv[0];
      acc[C_L1] += rq * Lv[1];
      acc[C_L3] += rq * Lv[3];
      if (D3) {
        const double T0 = rq * nxF[0], T1 = rq * nxF[1];
        if (plus) {
          acc[C_F2] += Fsv[2];
          acc[C_T0] += T0 + Msv[0];
          acc[C_T1] += T1 + Msv[1];
        } else {
          acc[C_F2] -= Fsv[2];
          acc[C_T0] += T0 - Msv[0];
          acc[C_T1] += T1 - Msv[1];
        }
        acc[C_L2] += rq * Lv[2];
        acc[C_L4] += rq * Lv[4];
        acc[C_L5] += rq * Lv[5];
      }
      if (peratom) {
        const double si = i_is_a ? 1.0 : -1.0;
        const double sq = plus ? si : -si;
        ev_tally_xyz_full(q, 0.0, 0.0, sq * Fv[0], sq * Fv[1], sq * Fv[2], delx, dely, delz);
      }
      if (counted) {
        acc[C_NL] += 1.0;
        if (cross) acc[C_NC] += 1.0;
      }
    };
    apply(i, true, -dx, -dy, -dz);
    if (vglobal) {
      // the global virial of the pair, -R (x) F_a: ev_tally_xyz_full's two halves (one per
      // automaton, 0.5 del_q (x) F_q each) summed here, or its one half when j is a ghost
      // (its owner tallies the other)
      const double w = jlocal ? -1.0 : -0.5;
      const double F0 = w * Fv[0], F1 = w * Fv[1], F2 = D3 ? w * Fv[2] : 0.0;
      vir[0] += R0 * F0;
      vir[1] += R1 * F1;
      vir[3] += R0 * F1;
      if (D3) {
        vir[2] += R2 * F2;
        vir[4] += R0 * F2;
        vir[5] += R1 * F2;
      }
    }
    if (jlocal) {
      apply(j, false, dx, dy, dz);
      // j's copy of the state: written when it is next read (sync_mirrors)
      any_mirror = true;
    }
    if (i_is_a && !attached) {
      if (linked) {
        tally_links += 1.0;
        if (cross) tally_cross += 1.0;
      } else
        tally_contacts += 1.0;
    }
  };
  // pass 1a for one pair of i (entry jj of its evaluation list): the relative position and
  // velocities (a pair with no state that does not touch is left out), its state and its
  // partners' inputs, into the batch
  int npre = 0;
  const bool common = ADV && !init_links && batch_on;
  // (stage and flush are inlined where the driver below calls them: as calls through their
  // closures the 2D pair loop ran 10 % slower, before it had a fused kernel)
  auto stage = [&](const int i, const bigint eoff, const int jj) __attribute__((always_inline)) {
      // the pairs i evaluates (rebuild_cache): partner, orientation, image and body flags
      const int *ej_i = &ej[eoff], *ef_i = &eflag[eoff];
      const int *cache_i = &cacheflat[eoff];
      // (the pair states are read from psc in the lists' order: one stream that the hardware
      // prefetcher follows)
      const double *psc_i = psc + eoff * NP - 1;
      const int j = ej_i[jj];
      const int ef = ef_i[jj];
      const double dbar = UNI ? dbar_u : radius[i] + radius[j];
      const bool i_is_a = ef & E_IA;
      const int a = i_is_a ? i : j, b = i_is_a ? j : i;
      // canonical relative position a -> b and velocities, bit-identical on every rank that
      // evaluates the pair (see image_shifts)
      double R0, R1, R2 = 0.0, Va0, Va1, Va2 = 0.0, Vb0, Vb1, Vb2 = 0.0;
      if (!(ef & E_IMAGE)) {
        // local partner or a plain copy of a remote atom: both ranks hold the same numbers
        // (a row holds the atom's own x and v: for these pairs the same numbers as atom->x, v)
        const double *xa = xo0 + PR * a, *xb = xo0 + PR * b, *va = xa + R_V, *vb = xb + R_V;
        R0 = xb[0] - xa[0];
        R1 = xb[1] - xa[1];
        Va0 = va[0];
        Va1 = va[1];
        Vb0 = vb[0];
        Vb1 = vb[1];
        if (D3) {
          R2 = xb[2] - xa[2];
          Va2 = va[2];
          Vb2 = vb[2];
        }
      } else {
        int jimg[3];
        unpack_image(eimg[eoff + jj], jimg);
        // image of b relative to a (of the partner j: b's image if i is a, else minus a's)
        const double n0 = i_is_a ? jimg[0] : -jimg[0], n1 = i_is_a ? jimg[1] : -jimg[1];
        const double *xa = xo0 + PR * a, *xb = xo0 + PR * b;
        if (D3) {
          const double n2 = i_is_a ? jimg[2] : -jimg[2];
          R0 = (xb[0] - xa[0]) + (n0 * h[0] + n1 * h[5] + n2 * h[4]);
          R1 = (xb[1] - xa[1]) + (n1 * h[1] + n2 * h[3]);
          R2 = (xb[2] - xa[2]) + n2 * h[2];
          Va2 = xa[5];
          Vb2 = xb[5];
          if (vremap) {
            // fix deform remap v: an image moves with the box's rate of deformation
            Vb2 += n2 * hr[2];
          }
          Va0 = xa[3];
          Va1 = xa[4];
          Vb0 = xb[3];
          Vb1 = xb[4];
          if (vremap) {
            Vb0 += n0 * hr[0] + n1 * hr[5] + n2 * hr[4];
            Vb1 += n1 * hr[1] + n2 * hr[3];
          }
        } else {
          R0 = (xb[0] - xa[0]) + (n0 * h[0] + n1 * h[5]);
          R1 = (xb[1] - xa[1]) + n1 * h[1];
          Va0 = xa[3];
          Va1 = xa[4];
          Vb0 = xb[3];
          Vb1 = xb[4];
          if (vremap) {
            Vb0 += n0 * hr[0] + n1 * hr[5];
            Vb1 += n1 * hr[1];
          }
        }
      }
      const double rsq = D3 ? R0 * R0 + R1 * R1 + R2 * R2 : R0 * R0 + R1 * R1;
      const int k1 = cache_i[jj];
      // a pair with no state that does not touch: nothing to do (initial links aside)
      if (k1 < 0 && !init_links && rsq >= dbar * dbar) return;
      const int ip = npre++;
      B.i[ip] = i;
      B.ia[ip] = i_is_a ? 1.0 : 0.0;
      B.jj[ip] = jj;
      B.e[ip] = eoff + jj;
      B.ef[ip] = ef;
      B.soff[ip] = (eoff + jj) * NP - 1;    // (the entry's slot in psc)
      B.j[ip] = j;
      B.R0[ip] = R0;
      B.R1[ip] = R1;
      // (the law reads the velocities only as b's relative to a's: vr = (V_b - V_a) - ...)
      B.dV0[ip] = Vb0 - Va0;
      B.dV1[ip] = Vb1 - Va1;
      if (D3) {    // (2D: +0, never stored; Batch::get gives the general path its zeros)
        B.R2[ip] = R2;
        B.dV2[ip] = Vb2 - Va2;
      }
      B.rsq[ip] = rsq;
      if (!UNI) B.dbar[ip] = dbar;
      // (a pair without a slot gets one in pass 2b with xi = 0: no projection.  Only this
      // pair writes its slot, so pass 2b reads the same xi)
      B.hasxi[ip] = (ADV && k1 >= 0) ? 1.0 : 0.0;
      // inputs of pass 2a (the common case: an existing link, advanced)
      if (ADV && k1 >= 0) {
        const double *sl = &psc_i[jj * NP];
        const double *oa = xo0 + PR * a + R_OM, *ob = xo0 + PR * b + R_OM;
        const double *pa = xo0 + PR * a + R_XM, *pb = xo0 + PR * b + R_XM;
        B.kind[ip] = sl[FS::S_KIND];
        B.pn[ip] = sl[FS::S_PN];
        if (muni) {
          B.cd[ip] = cd_u;
          B.cr[ip] = cr_u;
        } else {
          const double A = UNI ? A_u : pair_area(dbar, DIM);
          link_damping(mat, rmass[a], rmass[b], UNI ? runi : radius[a], UNI ? runi : radius[b],
                       A, dbar, B.cd[ip], B.cr[ip]);
        }
        B.xi0[ip] = sl[FS::S_XI];
        B.xi1[ip] = sl[FS::S_XI + 1];
        B.rp0[ip] = sl[FS::S_RP];
        B.rp1[ip] = sl[FS::S_RP + 1];
        B.th2[ip] = sl[FS::S_TH + 2];
        B.oa2[ip] = oa[2];
        B.ob2[ip] = ob[2];
        B.Xbar[ip] = 0.5 * (pa[0] + pb[0]);
        B.D0[ip] = 0.5 * (pa[1] + pb[1]);
        B.D1[ip] = 0.5 * (pa[2] + pb[2]);
        B.D3[ip] = 0.5 * (pa[4] + pb[4]);
        if (D3) {
          B.xi2[ip] = sl[FS::S_XI + 2];
          B.rp2[ip] = sl[FS::S_RP + 2];
          B.th0[ip] = sl[FS::S_TH];
          B.th1[ip] = sl[FS::S_TH + 1];
          B.oa0[ip] = oa[0];
          B.oa1[ip] = oa[1];
          B.ob0[ip] = ob[0];
          B.ob1[ip] = ob[1];
          B.D2[ip] = 0.5 * (pa[3] + pb[3]);
          B.D4[ip] = 0.5 * (pa[5] + pb[5]);
          B.D5[ip] = 0.5 * (pa[6] + pb[6]);
        }
        if (!UNI) {
          B.ra[ip] = radius[a];
          B.rb[ip] = radius[b];
        }
      } else {
        B.kind[ip] = FS::FREE;    // (not the common case: pass 2b's general path)
        B.xi0[ip] = B.xi1[ip] = B.xi2[ip] = 0.0;
      }
  };
  // passes 1b, 2a and 2b of the staged pairs
  auto flush = [&]() __attribute__((always_inline)) {
  // pass 1b: the geometry of the batch's pairs (square roots and divisions in vectorised loops)
  batch_geometry<DIM, UNI>(npre, runi);

  // pass 2a: the common case for the whole batch -- an existing link (or weld, attachment)
  // advanced by one step that does not break -- in loops
  // without branches over the batch's arrays, which the compiler vectorises.  The same
  // expressions in the same order as the general path (pass 2b), so the same numbers; a pair
  // outside the common case (elig = 0) takes the general path with its state untouched
  if (common) batch_common<DIM, UNI>(npre, runi);

  // pass 2b: the law, pair by pair, in the order of the pairs (so that the sums into forces,
  // torques and stresses are formed in the same order as without batches)
  for (int ip = 0; ip < npre; ip++) {
      if (common && B.elig[ip]) {
        // the common case (pass 2a): write the advanced state back, apply the forces
        // (entry, flags and slot offset from pass 1: no chain of dependent loads here)
        const int i = B.i[ip], j = B.j[ip];
        const bigint e = B.e[ip];
        const int ef = B.ef[ip];
        const bool jlocal = ef & E_LOCAL;
        double *s = psc + B.soff[ip];
        if (jlocal && mirrorflat[e] < 0) {
          // (as in the general path below)
          const int kj = find_slot(j, (double) tag[i]);
          mirrorflat[e] = (kj >= 0) ? kj : new_slot(j, (double) tag[i]);
        }
        const double R0 = B.R0[ip], R1 = B.R1[ip], R2 = D3 ? B.R2[ip] : 0.0;
        s[FS::S_XI] = B.xi0n[ip];
        s[FS::S_XI + 1] = B.xi1n[ip];
        s[FS::S_RP] = R0;
        s[FS::S_RP + 1] = R1;
        s[FS::S_PN] = B.pnn[ip];
        s[FS::S_TH + 2] = B.th2n[ip];
        if (D3) {
          s[FS::S_XI + 2] = B.xi2n[ip];
          s[FS::S_RP + 2] = R2;
          s[FS::S_TH] = B.th0n[ip];
          s[FS::S_TH + 1] = B.th1n[ip];
        }
        const double Fv[3] = {B.F0[ip], B.F1[ip], D3 ? B.F2[ip] : 0.0};
        const double Fsv[3] = {B.Fs0[ip], B.Fs1[ip], D3 ? B.Fs2[ip] : 0.0};
        const double Msv[3] = {D3 ? B.Ms0[ip] : 0.0, D3 ? B.Ms1[ip] : 0.0, B.Ms2[ip]};
        const double nxFv[3] = {D3 ? B.nxF0[ip] : 0.0, D3 ? B.nxF1[ip] : 0.0, B.nxF2[ip]};
        const double Lv[6] = {B.L0[ip], B.L1[ip], D3 ? B.L2[ip] : 0.0, B.L3[ip],
                              D3 ? B.L4[ip] : 0.0, D3 ? B.L5[ip] : 0.0};
        scatter(i, j, jlocal, ef & E_IA, !(ef & E_SAME), static_cast<int>(B.kind[ip]), R0, R1, R2,
                Fv, Fsv, Msv, nxFv, Lv);
        continue;
      }
      PairPre P;
      B.get<D3>(ip, P);
      const int i = P.i;
      const double itag = (double) tag[i];
      const bigint eoff = cacheoff[i];
      const int *ef_i = &eflag[eoff];
      int *cache_i = &cacheflat[eoff];
      int *mirror_i = &mirrorflat[eoff];
      double *slots_i = slots + (bigint) i * slotrow;
      const int jj = P.jj;
      const int j = P.j;
      const int ef = ef_i[jj];
      const bool jlocal = ef & E_LOCAL;
      const double dbar = UNI ? dbar_u : radius[i] + radius[j];
      const bool i_is_a = ef & E_IA;
      const int a = i_is_a ? i : j, b = i_is_a ? j : i;
      const double R0 = P.R0, R1 = P.R1, R2 = P.R2;
      const double dV0 = P.dV0, dV1 = P.dV1, dV2 = P.dV2;
      const double rsq = P.rsq;
      int k = cache_i[jj];
      const bool same_body = ef & E_SAME;
      if (k < 0) {
        const double jtag = (double) tag[j];
        const int ikind = init_links ? initial_link_kind(i, tag[j], rsq, dbar, same_body) : FS::FREE;
        const bool mklink = ikind != FS::FREE;
        if (rsq >= dbar * dbar && !mklink) continue;
        k = new_slot(i, jtag);
        cache_i[jj] = k;
        if (jlocal) {
          const int kj = find_slot(j, itag);
          mirror_i[jj] = (kj >= 0) ? kj : new_slot(j, itag);
        }
        // (the new slot reserves k in i's row, its tag set; its state lives in psc)
        double *s = psc + (eoff + jj) * NP - 1;
        memcpy(s + 1, slots_i + k * FS::NSLOT + 1, sizeof(double) * NP);
        s[FS::S_KIND] = mklink ? ikind : FS::CONTACT;
        s[FS::S_RP + 0] = R0;
        s[FS::S_RP + 1] = R1;
        s[FS::S_RP + 2] = R2;
        // an initial link is stress-free at its current length
        if (mklink) s[FS::S_PN] = (std::sqrt(rsq) - dbar) / dbar;
      }
      double *s = psc + (eoff + jj) * NP - 1;
      // (a slot that is forgotten frees its place in i's row too)
      double *srow = slots_i + k * FS::NSLOT;
      if (jlocal && mirror_i[jj] < 0) {
        // j lost its copy (it held the pair as a ghost partner elsewhere): i's copy, which
        // was evaluated, is the state; j gets it back at the end of this pair
        const int kj = find_slot(j, itag);
        mirror_i[jj] = (kj >= 0) ? kj : new_slot(j, itag);
      }
      double *sj = jlocal ? slots + (bigint) j * slotrow + mirror_i[jj] * FS::NSLOT : nullptr;
      const double n0 = P.n0, n1 = P.n1, n2 = P.n2;
      const double idbar = P.idbar;
      const double eraw = P.eraw;
      int kind = static_cast<int>(s[FS::S_KIND]);
      const bool cross = !same_body;
      // forces, torques, Love-Weber sums and tallies of the pair
      auto tail = [&](double Fe0, double Fe1, double Fe2, double Fd0, double Fd1, double Fd2,
                      double Ma0, double Ma1, double Ma2, int kind) __attribute__((always_inline)) {
        // (the expressions of pass 2a's, pair_force)
        const double F0 = Fe0 + Fd0, F1 = Fe1 + Fd1, F2 = D3 ? Fe2 + Fd2 : 0.0;
        const double nxF0 = D3 ? n1 * F2 - n2 * F1 : 0.0, nxF1 = D3 ? n2 * F0 - n0 * F2 : 0.0;
        const double nxF2 = n0 * F1 - n1 * F0;
        const double L0 = n0 * Fe0, L1 = n1 * Fe1, L3 = 0.5 * (n0 * Fe1 + n1 * Fe0);
        const double L2 = D3 ? n2 * Fe2 : 0.0, L4 = D3 ? 0.5 * (n0 * Fe2 + n2 * Fe0) : 0.0,
                     L5 = D3 ? 0.5 * (n1 * Fe2 + n2 * Fe1) : 0.0;
        const double si = i_is_a ? 1.0 : -1.0;
        const double Fs0 = si * F0, Fs1 = si * F1, Fs2 = D3 ? si * F2 : 0.0;
        const double Ms0 = D3 ? si * Ma0 : 0.0, Ms1 = D3 ? si * Ma1 : 0.0, Ms2 = si * Ma2;
        const double Fv[3] = {F0, F1, F2}, Fsv[3] = {Fs0, Fs1, Fs2}, Msv[3] = {Ms0, Ms1, Ms2};
        const double nxFv[3] = {nxF0, nxF1, nxF2}, Lv[6] = {L0, L1, L2, L3, L4, L5};
        scatter(i, j, sj != nullptr, i_is_a, cross, kind, R0, R1, R2, Fv, Fsv, Msv, nxFv, Lv);
      };

      if (kind == FS::CONTACT && eraw >= 0.0) {    // contact opened: forget it
        memset(s + 1, 0, sizeof(double) * NP);
        memset(srow, 0, sizeof(double) * FS::NSLOT);
        cache_i[jj] = -1;
        if (sj) {
          memset(sj, 0, sizeof(double) * FS::NSLOT);
          mirror_i[jj] = -1;
        }
        continue;
      }

      const double ra = UNI ? runi : radius[a], rb = UNI ? runi : radius[b];
      const double *oa = xo0 + PR * a + R_OM, *ob = xo0 + PR * b + R_OM;
      // ws = ra omega_a + rb omega_b, wxn = ws x n (2D: ws along z)
      double wxn0, wxn1, wxn2 = 0.0;
      if (D3) {
        const double ws0 = ra * oa[0] + rb * ob[0], ws1 = ra * oa[1] + rb * ob[1],
                     ws2 = ra * oa[2] + rb * ob[2];
        wxn0 = ws1 * n2 - ws2 * n1;
        wxn1 = ws2 * n0 - ws0 * n2;
        wxn2 = ws0 * n1 - ws1 * n0;
      } else {
        const double ws2 = ra * oa[2] + rb * ob[2];
        wxn0 = -(ws2 * n1);
        wxn1 = ws2 * n0;
      }
      // velocity of b's contact point relative to a's
      const double vr0 = dV0 - wxn0, vr1 = dV1 - wxn1, vr2 = D3 ? dV2 - wxn2 : 0.0;
      double *xi = &s[FS::S_XI];
      double xi0 = xi[0], xi1 = xi[1], xi2 = D3 ? xi[2] : 0.0;
      const bool linked0 = (kind == FS::LINK || kind == FS::WELD || kind == FS::ATTACH);
      double pn = s[FS::S_PN];

      if (ADV) {
        // tangential displacement: keep xi in the tangent plane (magnitude conserved, the
        // factor sc from pass 1), then add the tangential part of this step's contact-point
        // displacement
        if (P.proj) {
          const double sc = P.sc, xn = P.xn;
          xi0 = sc * (xi0 - xn * n0);
          xi1 = sc * (xi1 - xn * n1);
          if (D3) xi2 = sc * (xi2 - xn * n2);
        }
        double *rp = &s[FS::S_RP];
        const double du0 = R0 - rp[0] - dt * wxn0, du1 = R1 - rp[1] - dt * wxn1;
        const double du2 = D3 ? R2 - rp[2] - dt * wxn2 : 0.0;
        const double dun = D3 ? du0 * n0 + du1 * n1 + du2 * n2 : du0 * n0 + du1 * n1;
        xi0 += du0 - dun * n0;
        xi1 += du1 - dun * n1;
        rp[0] = R0;
        rp[1] = R1;
        if (D3) {
          xi2 += du2 - dun * n2;
          rp[2] = R2;
        }
        if (linked0) {
          // plastic offsets: the pending plastic strain increments of a and b
          // (mean of the two halves of the pair) leave the elastic pair strain
          const double *pa = xo0 + PR * a + R_DEP, *pb = xo0 + PR * b + R_DEP;
          // (tensor order xx yy zz xy xz yz; in 2D the zz increment does not act on in-plane
          // pairs and xz, yz vanish)
          const double D0 = 0.5 * (pa[0] + pb[0]), D1 = 0.5 * (pa[1] + pb[1]),
                       D3xy = 0.5 * (pa[3] + pb[3]);
          if (D3) {
            const double D2 = 0.5 * (pa[2] + pb[2]), D4 = 0.5 * (pa[4] + pb[4]),
                         D5 = 0.5 * (pa[5] + pb[5]);
            const double dsum = std::fabs(D0) + std::fabs(D1) + std::fabs(D2) + std::fabs(D3xy) +
                std::fabs(D4) + std::fabs(D5);
            if (dsum > 0.0) {    // elastic automata have no offsets (the common case)
              const double Dn0 = D0 * n0 + D3xy * n1 + D4 * n2, Dn1 = D3xy * n0 + D1 * n1 + D5 * n2,
                           Dn2 = D4 * n0 + D5 * n1 + D2 * n2;
              const double nDn = n0 * Dn0 + n1 * Dn1 + n2 * Dn2;
              pn += nDn;
              xi0 -= dbar * (Dn0 - nDn * n0);
              xi1 -= dbar * (Dn1 - nDn * n1);
              xi2 -= dbar * (Dn2 - nDn * n2);
            }
            s[FS::S_TH + 0] += dt * (ob[0] - oa[0]);
            s[FS::S_TH + 1] += dt * (ob[1] - oa[1]);
          } else {
            const double dsum = std::fabs(D0) + std::fabs(D1) + std::fabs(D3xy);
            if (dsum > 0.0) {
              const double Dn0 = D0 * n0 + D3xy * n1, Dn1 = D3xy * n0 + D1 * n1;
              const double nDn = n0 * Dn0 + n1 * Dn1;
              pn += nDn;
              xi0 -= dbar * (Dn0 - nDn * n0);
              xi1 -= dbar * (Dn1 - nDn * n1);
            }
          }
          s[FS::S_TH + 2] += dt * (ob[2] - oa[2]);
        }
      }

      const double A = UNI ? A_u : pair_area(dbar, DIM);
      const double sf = G2 * idbar;    // shear_factor(mat, dbar)
      const double Xbar = 0.5 * (xo0[PR * a + R_XM] + xo0[PR * b + R_XM]);    // (see compute)
      double sn = 0.0, t0 = 0.0, t1 = 0.0, t2v = 0.0;

      if (linked0) {
        sn = G2 * (eraw - pn) + alpha * Xbar;    // link_normal
        t0 = sf * xi0;
        t1 = sf * xi1;
        if (D3) t2v = sf * xi2;
        const double t2 = D3 ? t0 * t0 + t1 * t1 + t2v * t2v : t0 * t0 + t1 * t1;
        const double strength = (kind == FS::LINK) ? mat.s0 : mat.wfac * mat.s0;
        if (ADV && kind != FS::ATTACH && link_breaks_sq(sn, t2, strength)) {
          if (i_is_a) {
            autom[i][FS::A_LB] += 1.0;
            if (cross) autom[i][FS::A_CB] += 1.0;
          }
          kind = FS::CONTACT;
          s[FS::S_KIND] = kind;
          pn = 0.0;
          for (int c = 0; c < 3; c++) s[FS::S_TH + c] = 0.0;
          if (eraw >= 0.0) {
            memset(s + 1, 0, sizeof(double) * NP);
            memset(srow, 0, sizeof(double) * FS::NSLOT);
            cache_i[jj] = -1;
            if (sj) {
              memset(sj, 0, sizeof(double) * FS::NSLOT);
              mirror_i[jj] = -1;
            }
            continue;
          }
        }
      }
      if (kind == FS::CONTACT) {
        sn = contact_normal(mat, eraw);
        t0 = sf * xi0;
        t1 = sf * xi1;
        if (D3) t2v = sf * xi2;
        const double t2 = D3 ? t0 * t0 + t1 * t1 + t2v * t2v : t0 * t0 + t1 * t1;
        const double cap = mat.mu * std::fabs(sn);
        // Coulomb: scale only when sliding (the square root only then)
        const double cs = (t2 > cap * cap && t2 > 0.0) ? coulomb_scale(mat, sn, std::sqrt(t2)) : 1.0;
        if (cs < 1.0) {
          xi0 *= cs;
          t0 *= cs;
          xi1 *= cs;
          t1 *= cs;
          if (D3) {
            xi2 *= cs;
            t2v *= cs;
          }
        }
        const double t2c = (cs < 1.0) ? cap * cap : t2;
        if (ADV && welds(mat, sn, t2c)) {
          kind = FS::WELD;
          s[FS::S_KIND] = kind;
          pn = weld_offset(mat, eraw, Xbar);
          if (i_is_a) {
            autom[i][FS::A_WF] += 1.0;
            if (cross) autom[i][FS::A_CF] += 1.0;
          }
        }
      }
      xi[0] = xi0;
      xi[1] = xi1;
      if (D3) xi[2] = xi2;
      s[FS::S_PN] = pn;
      const bool attached = (kind == FS::ATTACH);
      const bool linked = (kind == FS::LINK || kind == FS::WELD || attached);

      // elastic force on a
      const double Fe0 = A * (sn * n0 + t0), Fe1 = A * (sn * n1 + t1);
      const double Fe2 = D3 ? A * (sn * n2 + t2v) : 0.0;
      double Fd0, Fd1, Fd2 = 0.0, Ma0 = 0.0, Ma1 = 0.0, Ma2;
      if (!linked) {
        const double cv = UNI ? cv_u : viscous_factor(mat, A, dbar);
        Fd0 = cv * vr0;
        Fd1 = cv * vr1;
        if (D3) Fd2 = cv * vr2;
        Ma2 = 0.0;
      } else {
        // damping constants of the pair (fixed by masses and radii)
        double cd = cd_u, cr = cr_u;
        if (!muni) link_damping(mat, rmass[a], rmass[b], ra, rb, A, dbar, cd, cr);
        Fd0 = cd * vr0;
        Fd1 = cd * vr1;
        if (D3) Fd2 = cd * vr2;
        const double kr = UNI ? kr_u : rotational_stiffness(mat, A, dbar);
        const double *th = &s[FS::S_TH];
        if (D3) {
          Ma0 = kr * th[0] + cr * (ob[0] - oa[0]);
          Ma1 = kr * th[1] + cr * (ob[1] - oa[1]);
        }
        Ma2 = kr * th[2] + cr * (ob[2] - oa[2]);
      }

      tail(Fe0, Fe1, Fe2, Fd0, Fd1, Fd2, Ma0, Ma1, Ma2, kind);
  }
  npre = 0;
  };
  // the fused kernel (fused4) where it applies: one radius and one mass, a committed step,
  // no per-atom tallies
  const bool fused = MCA_FUSED && UNI && common && muni && !peratom && fused_on;
  FusedCtx fctx;
  fctx.h = h;
  fctx.hr = hr;
  fctx.vremap = vremap;
  fctx.vglobal = vglobal;
  fctx.dt = dt;
  fctx.G2 = G2;
  fctx.alpha = alpha;
  fctx.runi = runi;
  fctx.dbar_u = dbar_u;
  fctx.idbar_u = 1.0 / (runi + runi);    // (batch_geometry's)
  fctx.A_u = A_u;
  fctx.kr_u = kr_u;
  fctx.cd_u = cd_u;
  fctx.cr_u = cr_u;
  fctx.s_link = mat.s0;    // (batch_common's)
  fctx.s_weld = mat.wfac * mat.s0;
  // (its tallies and the virial pass through a copy: a local whose address is taken lives
  // in memory for the whole loop)
  auto fused_step = [&](bigint &e_, int &skip_) __attribute__((always_inline)) -> int {
    FusedIO io;
    io.e = e_;
    io.skip = 1;
    io.links = io.cross = 0.0;
    io.local = false;
    if (vglobal)
      for (int c = 0; c < 6; c++) io.vir[c] = vir[c];
    fctx.npre = npre;
    const int r = fused4<DIM>(fctx, io);
    if (r == 1) {
      e_ = io.e;
      tally_links += io.links;
      tally_cross += io.cross;
      tally_fused += 4.0;
      if (io.local) any_mirror = true;
      if (vglobal)
        for (int c = 0; c < 6; c++) vir[c] = io.vir[c];
    } else if (r == 0)
      skip_ = io.skip;
    return r;
  };
  // the pairs in the order of the evaluation lists, automaton ii, its entry jj.  (Each lambda
  // is inlined at its one call site: called through a closure, the locals it shares --
  // tallies, virial, npre -- live in memory, and the 2D pair loop ran 8-10 % slower)
  if (fused) {
    // the kernel takes the next four pairs where it can, the batch stages the others (the
    // lists hold the automata's entries one after another in ilist's order: one cursor e)
    bigint e = 0;
    int skip = 0;    // pairs the kernel left to the batch, still to stage
    for (;;) {
      const bool done = e >= nentries;
      bool full = false;
      if (!done) {
        // (a first pair without a link takes the batch without a call to the kernel)
        if (!skip && (cacheflat[e] < 0 || !(psc[e * NP + (FS::S_KIND - 1)] == FS::LINK ||
                                            psc[e * NP + (FS::S_KIND - 1)] == FS::WELD ||
                                            psc[e * NP + (FS::S_KIND - 1)] == FS::ATTACH)))
          skip = 1;
        const int r = skip ? 0 : fused_step(e, skip);
        if (r == 0) {
          skip--;
          const int i = eown[e];
          const bigint eoff = cacheoff[i];
          stage(i, eoff, (int) (e - eoff));
          e++;
          full = npre == NBATCH;
        } else
          full = r == 2;
      }
      if ((done || full) && npre) flush();
      if (done) break;
    }
  } else {
    // (a batch may end inside the pairs of an automaton: jj0 is where the next one resumes)
    int ii = 0, jj0 = 0;
    while (ii < inum) {
      for (; ii < inum && npre < NBATCH; ii++) {
        const int i = ilist[ii];
        const bigint eoff = cacheoff[i];
        const int jnum = ecount[i];
        int jj = jj0;
        for (; jj < jnum && npre < NBATCH; jj++) stage(i, eoff, jj);
        if (jj < jnum) {    // the batch is full: the rest of i's pairs start the next one
          jj0 = jj;
          break;
        }
        jj0 = 0;
      }
      flush();
    }
  }
  if (any_mirror) mirrors_pending = 1;
  psc_pending = 1;
  if (vglobal)
    for (int c = 0; c < 6; c++) virial[c] += vir[c];
  tally[0] = tally_links;
  tally[1] = tally_cross;
  tally[2] = tally_contacts;
  tally[3] = tally_fused;
}

/* ----------------------------------------------------------------------
   the fused kernel of pair_loop (one radius and one mass, a committed step,
   no per-atom tallies): the next four pairs of the evaluation lists --
   possibly of several automata -- when all four are in the common case, one
   pair per lane of AVX registers from their inputs to their sums, without
   the batch's arrays.  Inputs are loaded as rows (the partners' rows of xo,
   the pair states) and transposed in registers, results are transposed back
   into rows of the pair state and of sacc and added row by row.  The batch
   stages every value of a pair in memory and reads it back, which made the
   pair loop bound by its stores (docs/mca.md).  The expressions and their
   order are batch_geometry's and batch_common's for the dimension, the sums
   are formed pair by pair in the lists' order, so the numbers are the
   general path's (tests/mca/test_law_batch.py).  Returns 0, with nothing
   written, when a pair is not in the common case (no state, not linked, a
   mirror slot to find, a link that breaks): those take the batch; 2 when
   staged pairs must be flushed first; 1 when the four were taken.
   A function of its own (not inlined), so that its registers are its own:
   inlined into the pair loop it spilled about three times as many vectors.
------------------------------------------------------------------------- */

template <int DIM> int PairMCA::fused4(const FusedCtx &C, FusedIO &io)
{
#if MCA_FUSED
  constexpr bool D3 = (DIM == 3);
  const double *xo0 = xo[0];
  double *sacc0 = sacc[0];
  const double *h = C.h, *hr = C.hr;
  const double dt = C.dt, G2 = C.G2, alpha = C.alpha, runi = C.runi, dbar_u = C.dbar_u;
  const double idbar_u = C.idbar_u, A_u = C.A_u, kr_u = C.kr_u, cd_u = C.cd_u, cr_u = C.cr_u;
  const double s_link = C.s_link, s_weld = C.s_weld;
    // the four entries e0..e0+3: in the common case if each has a state (a slot) that is a
    // link, weld or attachment, and a local partner its mirror slot.  If not, the pairs up to
    // the last that is not go to the batch (io.skip) before the kernel is tried again: a window
    // that slid by one pair would meet the same pair up to four times (in a stretch of contacts
    // that was a quarter of the damaged 3D block's time)
    const bigint e0 = io.e;
    if (e0 + 4 > nentries) {
      io.skip = (int) (nentries - e0);
      return 0;
    }
    {
      const __m128i cf = _mm_loadu_si128(reinterpret_cast<const __m128i *>(cacheflat + e0));
      const __m128i mf = _mm_loadu_si128(reinterpret_cast<const __m128i *>(mirrorflat + e0));
      const __m128i fl = _mm_loadu_si128(reinterpret_cast<const __m128i *>(eflag + e0));
      const __m128i loc = _mm_cmpeq_epi32(_mm_and_si128(fl, _mm_set1_epi32(E_LOCAL)),
                                          _mm_set1_epi32(E_LOCAL));
      const __m128i bad = _mm_or_si128(_mm_srai_epi32(cf, 31), _mm_and_si128(loc, _mm_srai_epi32(mf, 31)));
      int badl = _mm_movemask_ps(_mm_castsi128_ps(bad));
      // (a lane without a slot has no state in psc: its kind is not read)
      for (int l = 0; l < 4; l++) {
        if (badl >> l & 1) continue;
        const double kd = psc[(e0 + l) * NP + (FS::S_KIND - 1)];
        if (!(kd == FS::LINK || kd == FS::WELD || kd == FS::ATTACH)) badl |= 1 << l;
      }
      // (no four that start at or before the last lane not taken can be taken: up to it, the
      // batch)
      if (badl) {
        io.skip = 32 - __builtin_clz(badl);
        return 0;
      }
    }
    // (the staged pairs come first in the lists' order: flushed before the four are computed,
    // not after -- in a mixed stretch of contacts and links that doubled the kernel's work)
    if (C.npre) return 2;
    const int *li = eown + e0, *lj = ej + e0, *lef = eflag + e0;
    const bigint le[4] = {e0, e0 + 1, e0 + 2, e0 + 3};
    bool anyimg = false, anylocal = false;
    for (int l = 0; l < 4; l++) {
      anyimg = anyimg || (lef[l] & E_IMAGE);
      anylocal = anylocal || (lef[l] & E_LOCAL);
    }
    const V4 zero = vb(0.0), half = vb(0.5);
    const V4 mIA = vne(_mm256_setr_pd(lef[0] & E_IA, lef[1] & E_IA, lef[2] & E_IA, lef[3] & E_IA), zero);
    static_assert(R_X == 0 && R_V == 3 && R_OM == 6 && R_XM == 9 && R_DEP == 10 && PR == 16,
                  "the fused kernel reads rows of xo in blocks of four");
    const double *pa[4], *pb[4];
    for (int l = 0; l < 4; l++) {
      const bool ia = lef[l] & E_IA;
      pa[l] = xo0 + PR * (ia ? li[l] : lj[l]);
      pb[l] = xo0 + PR * (ia ? lj[l] : li[l]);
    }
    // periodic images: pass 1a's shifts (b's position, and its velocity with fix deform's
    // remap v), lane by lane
    alignas(32) double sR[3][4], sV[3][4], im[4];
    if (anyimg) {
      for (int l = 0; l < 4; l++) {
        im[l] = (lef[l] & E_IMAGE) ? 1.0 : 0.0;
        for (int c = 0; c < 3; c++) sR[c][l] = sV[c][l] = 0.0;
        if (!(lef[l] & E_IMAGE)) continue;
        int jimg[3];
        unpack_image(eimg[le[l]], jimg);
        const bool i_is_a = lef[l] & E_IA;
        const double n0 = i_is_a ? jimg[0] : -jimg[0], n1 = i_is_a ? jimg[1] : -jimg[1];
        if constexpr (D3) {
          const double n2 = i_is_a ? jimg[2] : -jimg[2];
          sR[0][l] = (n0 * h[0] + n1 * h[5] + n2 * h[4]);
          sR[1][l] = (n1 * h[1] + n2 * h[3]);
          sR[2][l] = n2 * h[2];
          sV[0][l] = n0 * hr[0] + n1 * hr[5] + n2 * hr[4];
          sV[1][l] = n1 * hr[1] + n2 * hr[3];
          sV[2][l] = n2 * hr[2];
        } else {
          sR[0][l] = (n0 * h[0] + n1 * h[5]);
          sR[1][l] = n1 * h[1];
          sV[0][l] = n0 * hr[0] + n1 * hr[5];
          sV[1][l] = n1 * hr[1];
        }
      }
    }
    const bool vshift = anyimg && C.vremap;
    const V4 vrq = vb(runi);
    const V4 si = vsel(mIA, vb(1.0), vb(-1.0));
    // what the sums below read: the pair's vector R (a to b), normal, elastic force Fe, force
    // F and signed moment Ms on i, kind (2D: the z components are neither formed nor read)
    V4 R0, R1, R2, n0, n1, n2, Fe0, Fe1, Fe2, F0, F1, F2, Ms0, Ms1, Ms2, kind;
    // (what both dimensions do alike)
    // a block: row(l) of lanes 0..3, transposed (a: the first value of the four lanes, ...)
    auto rows4 = [&](auto row, V4 &a, V4 &b, V4 &c, V4 &d) __attribute__((always_inline)) {
      a = row(0);
      b = row(1);
      c = row(2);
      d = row(3);
      transpose4(a, b, c, d);
    };
    // component c of R: (x_b - x_a) + shift where the pair is an image (pass 1a's order)
    auto image_shift = [&](V4 &Rc, int c) __attribute__((always_inline)) {
      Rc = vsel(vne(_mm256_load_pd(im), zero), Rc + _mm256_load_pd(sR[c]), Rc);
    };
    double *const sp[4] = {psc + le[0] * NP, psc + le[1] * NP, psc + le[2] * NP, psc + le[3] * NP};
    // the rows' omega_z X dep_xx dep_yy (3D block 2): r omega_a + r omega_b (ws2), omega_b -
    // omega_a (dom2), 0.5 (X_a + X_b), the plastic strain increments (a sum: the same numbers
    // as pass 1a's)
    V4 dom2, ws2, Xbar, D0, D1;
    auto omega_z_block = [&]() __attribute__((always_inline)) {
      auto row = [&](int l, V4 &g) __attribute__((always_inline)) {
        const V4 av = _mm256_loadu_pd(pa[l] + R_OM + 2), bv = _mm256_loadu_pd(pb[l] + R_OM + 2);
        g = bv - av;
        return V4(_mm256_blend_pd(av + bv, vrq * av + vrq * bv, 0x1));
      };
      V4 g0, g1, g2, g3;
      V4 c0 = row(0, g0), c1 = row(1, g1), c2 = row(2, g2), c3 = row(3, g3);
      transpose4(c0, c1, c2, c3);
      ws2 = c0;
      Xbar = half * c1;
      D0 = half * c2;
      D1 = half * c3;
      dom2 = _mm256_permute2f128_pd(_mm256_unpacklo_pd(g0, g1), _mm256_unpacklo_pd(g2, g3), 0x20);
    };
    // the factor that keeps xi's magnitude when it is turned into the tangent plane
    // (batch_geometry), and whether it applies
    auto tangent_scale = [&](V4 xn, V4 m0, V4 &proj) __attribute__((always_inline)) {
      proj = _mm256_and_pd(vne(xn, zero), vgt(m0, zero));
      const V4 q = xn * xn / m0;
      V4 sc = vb(1.0) + q * (vb(0.5) + vb(0.375) * q);
      const V4 series = vlt(q, vb(1e-4));
      // (the square root only where a lane needs it: one division and one square root less
      // per four pairs in the common case, whose normals turn by ~1e-6 rad per step)
      if (_mm256_movemask_pd(_mm256_andnot_pd(series, proj)))
        sc = vsel(series, sc, vsel(vlt(q, vb(1.0)), _mm256_sqrt_pd(vb(1.0) / (vb(1.0) - q)), zero));
      return sc;
    };
    // the lanes whose link breaks on this step (t2: |t|^2)
    auto breaking = [&](V4 sn, V4 t2) __attribute__((always_inline)) {
      const V4 strength = vsel(veq(kind, vb(FS::LINK)), vb(s_link), vb(s_weld));
      const V4 tp = vsel(vgt(sn, zero), sn, zero);
      const V4 brk = _mm256_and_pd(vne(kind, vb(FS::ATTACH)),
                                   vgt(tp * tp + vb(3.0) * t2, strength * strength));
      return _mm256_movemask_pd(brk);
    };
    // four values of each lane's pair state entry, from offset off on, and back (c_v: value v
    // of the four lanes)
    auto get_state = [&](int off, V4 &c0, V4 &c1, V4 &c2, V4 &c3) __attribute__((always_inline)) {
      rows4([&](int l) { return V4(_mm256_loadu_pd(sp[l] + off)); }, c0, c1, c2, c3);
    };
    auto put_state = [&](int off, V4 c0, V4 c1, V4 c2, V4 c3) __attribute__((always_inline)) {
      transpose4(c0, c1, c2, c3);
      _mm256_storeu_pd(sp[0] + off, c0);
      _mm256_storeu_pd(sp[1] + off, c1);
      _mm256_storeu_pd(sp[2] + off, c2);
      _mm256_storeu_pd(sp[3] + off, c3);
    };
    if constexpr (D3) {
    // the rows of xo of a and b (i is a where E_IA: pass 1a's canonical orientation): x v omega
    // X dep (pair_mca.h, R_*), four blocks of four.  Per lane, b's row minus a's gives R, dV and
    // b's rotation rate relative to a's; the rows' sum the symmetric inputs, 0.5 (X_a + X_b) and
    // the plastic strain increments (a sum: the same numbers as pass 1a's); r (omega_a +
    // omega_b) the rotation term of the contact point (ra = rb = runi).  Then one transpose
    // per block gives one vector per quantity, one lane per pair
    // block 0 (x, v0): R, dV0
    V4 dV0;
    {
      // (named vectors, not arrays: GCC keeps an array of vectors in memory)
      auto row = [&](int l) __attribute__((always_inline)) {
        V4 bv = _mm256_loadu_pd(pb[l]);
        // ((V_b + shift) - V_a, pass 1a's order)
        if (vshift && im[l] != 0.0)
          bv = _mm256_blend_pd(bv, bv + _mm256_setr_pd(0.0, 0.0, 0.0, sV[0][l]), 0x8);
        return bv - _mm256_loadu_pd(pa[l]);
      };
      rows4(row, R0, R1, R2, dV0);
      if (anyimg) {
        image_shift(R0, 0);
        image_shift(R1, 1);
        image_shift(R2, 2);
      }
    }
    // pass 1b (batch_geometry)
    const V4 rsq = R0 * R0 + R1 * R1 + R2 * R2;
    const V4 r = _mm256_sqrt_pd(rsq);
    const V4 ir = vb(1.0) / r;
    n0 = R0 * ir;
    n1 = R1 * ir;
    n2 = R2 * ir;
    const V4 idbar = vb(idbar_u);
    const V4 eraw = r * idbar - vb(1.0);
    // block 1 (v1 v2, omega0 omega1): dV1 dV2, dom0 dom1 (omega_b - omega_a), ws0 ws1
    V4 dV1, dV2, dom0, dom1, ws0, ws1;
    {
      auto row = [&](int l, V4 &w) __attribute__((always_inline)) {
        const V4 av = _mm256_loadu_pd(pa[l] + 4);
        V4 bv = _mm256_loadu_pd(pb[l] + 4);
        w = vrq * av + vrq * bv;
        if (vshift && im[l] != 0.0)
          bv = _mm256_blend_pd(bv, bv + _mm256_setr_pd(sV[1][l], sV[2][l], 0.0, 0.0), 0x3);
        return bv - av;
      };
      V4 w0, w1, w2, w3;
      dV1 = row(0, w0);
      dV2 = row(1, w1);
      dom0 = row(2, w2);
      dom1 = row(3, w3);
      transpose4(dV1, dV2, dom0, dom1);
      transpose4(w0, w1, w2, w3);
      ws0 = w2;
      ws1 = w3;
    }
    // block 2 (omega2, X, dep xx yy): ws2 dom2, Xbar, D0 D1
    omega_z_block();
    // the contact point's rotation term and the relative velocity (batch_common)
    const V4 wxn0 = ws1 * n2 - ws2 * n1, wxn1 = ws2 * n0 - ws0 * n2, wxn2 = ws0 * n1 - ws1 * n0;
    const V4 vr0 = dV0 - wxn0, vr1 = dV1 - wxn1, vr2 = dV2 - wxn2;
    // block 3 (dep zz xy xz yz), and the plastic part of the pair's strain increment (applied
    // below, after the tangential update, in batch_common's order)
    V4 pl, nDn, cor0, cor1, cor2;
    {
      auto row = [&](int l) __attribute__((always_inline)) {
        return V4(_mm256_loadu_pd(pa[l] + 12) + _mm256_loadu_pd(pb[l] + 12));
      };
      V4 c0, c1, c2, c3;
      rows4(row, c0, c1, c2, c3);
      const V4 D2 = half * c0, D3xy = half * c1, D4 = half * c2, D5 = half * c3;
      const V4 dsum = vabs(D0) + vabs(D1) + vabs(D2) + vabs(D3xy) + vabs(D4) + vabs(D5);
      const V4 Dn0 = D0 * n0 + D3xy * n1 + D4 * n2, Dn1 = D3xy * n0 + D1 * n1 + D5 * n2,
               Dn2 = D4 * n0 + D5 * n1 + D2 * n2;
      nDn = n0 * Dn0 + n1 * Dn1 + n2 * Dn2;
      pl = vgt(dsum, zero);
      const V4 vdbar = vb(dbar_u);
      cor0 = vdbar * (Dn0 - nDn * n0);
      cor1 = vdbar * (Dn1 - nDn * n1);
      cor2 = vdbar * (Dn2 - nDn * n2);
    }
    // the pair states: kind pn xi th rp (psc entries, pair_mca.h)
    V4 pn, xi0, xi1, xi2, th0, th1, th2;
    get_state(0, kind, pn, xi0, xi1);
    get_state(4, xi2, th0, th1, th2);
    {
      const V4 xn = xi0 * n0 + xi1 * n1 + xi2 * n2;
      V4 proj;
      const V4 sc = tangent_scale(xn, xi0 * xi0 + xi1 * xi1 + xi2 * xi2, proj);
      // pass 2a (batch_common): the projection
      xi0 = vsel(proj, sc * (xi0 - xn * n0), xi0);
      xi1 = vsel(proj, sc * (xi1 - xn * n1), xi1);
      xi2 = vsel(proj, sc * (xi2 - xn * n2), xi2);
    }
    const V4 vdt = vb(dt);
    {
      V4 rp0 = load3(sp[0] + 8), rp1 = load3(sp[1] + 8), rp2 = load3(sp[2] + 8),
         rpx = load3(sp[3] + 8);
      transpose4(rp0, rp1, rp2, rpx);
      const V4 du0 = R0 - rp0 - vdt * wxn0, du1 = R1 - rp1 - vdt * wxn1,
               du2 = R2 - rp2 - vdt * wxn2;
      const V4 dun = du0 * n0 + du1 * n1 + du2 * n2;
      xi0 = xi0 + (du0 - dun * n0);
      xi1 = xi1 + (du1 - dun * n1);
      xi2 = xi2 + (du2 - dun * n2);
    }
    pn = vsel(pl, pn + nDn, pn);
    xi0 = vsel(pl, xi0 - cor0, xi0);
    xi1 = vsel(pl, xi1 - cor1, xi1);
    xi2 = vsel(pl, xi2 - cor2, xi2);
    th0 = th0 + vdt * dom0;
    th1 = th1 + vdt * dom1;
    th2 = th2 + vdt * dom2;
    const V4 vG2 = vb(G2);
    const V4 sf = vG2 * idbar;
    const V4 sn = vG2 * (eraw - pn) + vb(alpha) * Xbar;
    const V4 t0 = sf * xi0, t1 = sf * xi1, t2v = sf * xi2;
    // (the pair's forces before the rupture test, which rarely fails: fewer values live)
    const V4 vA = vb(A_u), vcd = vb(cd_u), vcr = vb(cr_u), vkr = vb(kr_u);
    Fe0 = vA * (sn * n0 + t0);
    Fe1 = vA * (sn * n1 + t1);
    Fe2 = vA * (sn * n2 + t2v);
    F0 = Fe0 + vcd * vr0;
    F1 = Fe1 + vcd * vr1;
    F2 = Fe2 + vcd * vr2;
    Ms0 = si * (vkr * th0 + vcr * dom0);
    Ms1 = si * (vkr * th1 + vcr * dom1);
    Ms2 = si * (vkr * th2 + vcr * dom2);
    // a link breaks: the batch's general path, from the pair before it on
    if (const int bm = breaking(sn, t0 * t0 + t1 * t1 + t2v * t2v)) {
      io.skip = 32 - __builtin_clz(bm);
      return 0;
    }
    static_assert(FS::S_PN == FS::S_KIND + 1 && FS::S_XI == FS::S_KIND + 2 &&
                      FS::S_TH == FS::S_KIND + 5 && FS::S_RP == FS::S_KIND + 8 && NP == 11,
                  "the fused kernel moves pair states in blocks of four");
    // the advanced state, back into the entries (kind unchanged), four values at a time
    put_state(0, kind, pn, xi0, xi1);
    put_state(4, xi2, th0, th1, th2);
    {
      V4 c0 = R0, c1 = R1, c2 = R2, c3 = R2;
      transpose4(c0, c1, c2, c3);
      store3(sp[0] + 8, c0);
      store3(sp[1] + 8, c1);
      store3(sp[2] + 8, c2);
      store3(sp[3] + 8, c3);
    }
    } else {
    // 2D: of the rows of xo, x0 x1 and v0 v1 (two halves of one vector), omega_z X dep_xx
    // dep_yy (one block of four) and dep_xy (a value); of the pair states, kind pn xi0 xi1 and
    // th1 th2 rp0 rp1 (th1 is 0 in 2D and written back as read).  The expressions are
    // batch_geometry's and batch_common's 2D branches (no z terms: those would turn a -0 into
    // a +0 where the batch keeps it)
    V4 dV0, dV1;
    {
      auto row = [&](int l) __attribute__((always_inline)) {
        // (x0 x1 | v0 v1)
        const V4 av = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(pa[l])),
                                           _mm_loadu_pd(pa[l] + R_V), 1);
        V4 bv = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(pb[l])),
                                     _mm_loadu_pd(pb[l] + R_V), 1);
        // ((V_b + shift) - V_a, pass 1a's order)
        if (vshift && im[l] != 0.0)
          bv = _mm256_blend_pd(bv, bv + _mm256_setr_pd(0.0, 0.0, sV[0][l], sV[1][l]), 0xC);
        return bv - av;
      };
      rows4(row, R0, R1, dV0, dV1);
      if (anyimg) {
        image_shift(R0, 0);
        image_shift(R1, 1);
      }
    }
    // pass 1b (batch_geometry)
    const V4 rsq = R0 * R0 + R1 * R1;
    const V4 r = _mm256_sqrt_pd(rsq);
    const V4 ir = vb(1.0) / r;
    n0 = R0 * ir;
    n1 = R1 * ir;
    const V4 idbar = vb(idbar_u);
    const V4 eraw = r * idbar - vb(1.0);
    // (omega2, X, dep xx yy): ws2 dom2, Xbar, D0 D1
    omega_z_block();
    // dep_xy
    const int XY = R_DEP + 3;
    const V4 D3xy = half * (_mm256_setr_pd(pa[0][XY], pa[1][XY], pa[2][XY], pa[3][XY]) +
                            _mm256_setr_pd(pb[0][XY], pb[1][XY], pb[2][XY], pb[3][XY]));
    // the contact point's rotation term (ws along z) and the relative velocity
    const V4 wxn0 = -(ws2 * n1), wxn1 = ws2 * n0;
    const V4 vr0 = dV0 - wxn0, vr1 = dV1 - wxn1;
    // the pair states
    V4 pn, xi0, xi1, th1, th2, rp0, rp1;
    get_state(0, kind, pn, xi0, xi1);
    get_state(6, th1, th2, rp0, rp1);
    {
      const V4 xn = xi0 * n0 + xi1 * n1;
      V4 proj;
      const V4 sc = tangent_scale(xn, xi0 * xi0 + xi1 * xi1, proj);
      xi0 = vsel(proj, sc * (xi0 - xn * n0), xi0);
      xi1 = vsel(proj, sc * (xi1 - xn * n1), xi1);
    }
    const V4 vdt = vb(dt);
    {
      const V4 du0 = R0 - rp0 - vdt * wxn0, du1 = R1 - rp1 - vdt * wxn1;
      const V4 dun = du0 * n0 + du1 * n1;
      xi0 = xi0 + (du0 - dun * n0);
      xi1 = xi1 + (du1 - dun * n1);
    }
    {
      const V4 dsum = vabs(D0) + vabs(D1) + vabs(D3xy);
      const V4 Dn0 = D0 * n0 + D3xy * n1, Dn1 = D3xy * n0 + D1 * n1;
      const V4 nDn = n0 * Dn0 + n1 * Dn1;
      const V4 pl = vgt(dsum, zero);
      const V4 vdbar = vb(dbar_u);
      pn = vsel(pl, pn + nDn, pn);
      xi0 = vsel(pl, xi0 - vdbar * (Dn0 - nDn * n0), xi0);
      xi1 = vsel(pl, xi1 - vdbar * (Dn1 - nDn * n1), xi1);
    }
    th2 = th2 + vdt * dom2;
    const V4 vG2 = vb(G2);
    const V4 sf = vG2 * idbar;
    const V4 sn = vG2 * (eraw - pn) + vb(alpha) * Xbar;
    const V4 t0 = sf * xi0, t1 = sf * xi1;
    const V4 vA = vb(A_u), vcd = vb(cd_u);
    Fe0 = vA * (sn * n0 + t0);
    Fe1 = vA * (sn * n1 + t1);
    F0 = Fe0 + vcd * vr0;
    F1 = Fe1 + vcd * vr1;
    Ms2 = si * (vb(kr_u) * th2 + vb(cr_u) * dom2);
    if (const int bm = breaking(sn, t0 * t0 + t1 * t1)) {
      io.skip = 32 - __builtin_clz(bm);
      return 0;
    }
    put_state(0, kind, pn, xi0, xi1);
    put_state(6, th1, th2, R0, R1);
    }
    if (C.vglobal) {
      // scatter's global virial, pair by pair in order
      alignas(32) double f0[4], f1[4], f2[4], x0[4], x1[4], x2[4];
      _mm256_store_pd(f0, F0);
      _mm256_store_pd(f1, F1);
      _mm256_store_pd(x0, R0);
      _mm256_store_pd(x1, R1);
      if constexpr (D3) {
        _mm256_store_pd(f2, F2);
        _mm256_store_pd(x2, R2);
      }
      for (int l = 0; l < 4; l++) {
        const double w = (lef[l] & E_LOCAL) ? -1.0 : -0.5;
        const double G0 = w * f0[l], G1 = w * f1[l];
        io.vir[0] += x0[l] * G0;
        io.vir[1] += x1[l] * G1;
        io.vir[3] += x0[l] * G1;
        if constexpr (D3) {
          const double G2w = w * f2[l];
          io.vir[2] += x2[l] * G2w;
          io.vir[4] += x0[l] * G2w;
          io.vir[5] += x1[l] * G2w;
        }
      }
    }
    // rows of sacc (C_*: F0 F1 T2 L0 | L1 L3 NL NC | F2 T0 T1 L2 | L4 L5 - -): one block of
    // four at a time, added to i's row and, when j is local, to j's (F_b = -F_a, M_b = -M_a:
    // acc - x is acc + (-x)), lane by lane in the lists' order
    static_assert(C_F0 == 0 && C_F1 == 1 && C_T2 == 2 && C_L0 == 3 && C_L1 == 4 && C_L3 == 5 &&
                      C_NL == 6 && C_NC == 7 && C_F2 == 8 && C_T0 == 9 && C_T1 == 10 &&
                      C_L2 == 11 && C_L4 == 12 && C_L5 == 13 && SR == 16,
                  "the fused kernel adds sacc rows in blocks of four");
    // (the rows of the four lanes' i and local j, once for the four blocks)
    double *const ai0 = sacc0 + SR * li[0], *const ai1 = sacc0 + SR * li[1],
                  *const ai2 = sacc0 + SR * li[2], *const ai3 = sacc0 + SR * li[3];
    double *const aj0 = (lef[0] & E_LOCAL) ? sacc0 + SR * lj[0] : nullptr;
    double *const aj1 = (lef[1] & E_LOCAL) ? sacc0 + SR * lj[1] : nullptr;
    double *const aj2 = (lef[2] & E_LOCAL) ? sacc0 + SR * lj[2] : nullptr;
    double *const aj3 = (lef[3] & E_LOCAL) ? sacc0 + SR * lj[3] : nullptr;
    const bool same1 = li[1] == li[0], same2 = li[2] == li[1], same3 = li[3] == li[2];
    auto add_rows = [&](int off, V4 c0, V4 c1, V4 c2, V4 c3, bool jsame, V4 d0, V4 d1, V4 d2,
                        V4 d3) __attribute__((always_inline)) {
      transpose4(c0, c1, c2, c3);
      if (jsame) {
        d0 = c0;
        d1 = c1;
        d2 = c2;
        d3 = c3;
      } else if (anylocal)
        transpose4(d0, d1, d2, d3);
      // (i's row stays in a register while consecutive lanes share i; j differs from the i of
      // its own lane, and a later lane's i reads its row after this lane's j wrote it)
      auto jadd = [&](double *aj, V4 d) __attribute__((always_inline)) {
        if (aj) _mm256_storeu_pd(aj + off, _mm256_loadu_pd(aj + off) + d);
      };
      V4 acc = _mm256_loadu_pd(ai0 + off) + c0;
      auto iadd = [&](bool same, double *prev, double *ai, V4 c) __attribute__((always_inline)) {
        if (same)
          acc = acc + c;
        else {
          _mm256_storeu_pd(prev + off, acc);
          acc = _mm256_loadu_pd(ai + off) + c;
        }
      };
      jadd(aj0, d0);
      iadd(same1, ai0, ai1, c1);
      jadd(aj1, d1);
      iadd(same2, ai1, ai2, c2);
      jadd(aj2, d2);
      iadd(same3, ai2, ai3, c3);
      jadd(aj3, d3);
      _mm256_storeu_pd(ai3 + off, acc);
    };
    {
      const V4 Fs0 = si * F0, Fs1 = si * F1, T2 = vrq * (n0 * F1 - n1 * F0);
      const V4 L0 = vrq * (n0 * Fe0);
      add_rows(C_F0, Fs0, Fs1, T2 + Ms2, L0, false, -Fs0, -Fs1, T2 - Ms2, L0);
    }
    {
      // link counts: every pair here is linked; attachments are not links
      const V4 notatt = vne(kind, vb(FS::ATTACH));
      const V4 cross = _mm256_setr_pd(!(lef[0] & E_SAME), !(lef[1] & E_SAME),
                                      !(lef[2] & E_SAME), !(lef[3] & E_SAME));
      const V4 L1 = vrq * (n1 * Fe1), L3 = vrq * (half * (n0 * Fe1 + n1 * Fe0));
      add_rows(C_L1, L1, L3, _mm256_and_pd(notatt, vb(1.0)), _mm256_and_pd(notatt, cross), true,
               zero, zero, zero, zero);
      const int na = _mm256_movemask_pd(notatt);
      for (int l = 0; l < 4; l++)
        if ((lef[l] & E_IA) && (na >> l & 1)) {
          io.links += 1.0;
          if (!(lef[l] & E_SAME)) io.cross += 1.0;
        }
    }
    if constexpr (D3) {
    {
      const V4 Fs2 = si * F2;
      const V4 T0 = vrq * (n1 * F2 - n2 * F1), T1 = vrq * (n2 * F0 - n0 * F2);
      const V4 L2 = vrq * (n2 * Fe2);
      add_rows(C_F2, Fs2, T0 + Ms0, T1 + Ms1, L2, false, -Fs2, T0 - Ms0, T1 - Ms1, L2);
    }
    {
      const V4 L4 = vrq * (half * (n0 * Fe2 + n2 * Fe0)), L5 = vrq * (half * (n1 * Fe2 + n2 * Fe1));
      add_rows(C_L4, L4, L5, zero, zero, true, zero, zero, zero, zero);
    }
    }
    if (anylocal) io.local = true;
  io.e = e0 + 4;
  return 1;
#else
  (void) C;
  (void) io;
  return 0;
#endif
}

/* ----------------------------------------------------------------------
   pass 1b of pair_loop: distance, normal, raw strain and the rescaling of the
   tangential displacement that keeps its magnitude when it is turned into
   the new tangent plane, for every pair of a batch (branches are selects)
------------------------------------------------------------------------- */

template <int DIM, bool UNI> void PairMCA::batch_geometry(int n, double runi)
{
  constexpr bool D3 = (DIM == 3);
  Batch &B = *bat;
  const double idbar_u = 1.0 / (runi + runi);
  for (int p = 0; p < n; p++) {    // vectorised x4 (tests/mca/test_law_vectorised.py)
    const double r = std::sqrt(B.rsq[p]);
    const double ir = 1.0 / r;
    const double n0 = B.R0[p] * ir, n1 = B.R1[p] * ir, n2 = D3 ? B.R2[p] * ir : 0.0;
    const double idbar = UNI ? idbar_u : 1.0 / B.dbar[p];
    B.r[p] = r;
    B.n0[p] = n0;
    B.n1[p] = n1;
    B.n2[p] = n2;
    B.idbar[p] = idbar;
    B.eraw[p] = r * idbar - 1.0;
    const double xi0 = B.xi0[p], xi1 = B.xi1[p], xi2 = D3 ? B.xi2[p] : 0.0;
    const double xn = D3 ? xi0 * n0 + xi1 * n1 + xi2 * n2 : xi0 * n0 + xi1 * n1;
    const double m0 = D3 ? xi0 * xi0 + xi1 * xi1 + xi2 * xi2 : xi0 * xi0 + xi1 * xi1;
    // projection removes xn^2 of |xi|^2; restore the magnitude, sqrt(m0/(m0 - xn^2)).
    // The normal turns by ~1e-6 rad per step, so q = xn^2/m0 ~ 1e-12 and the series
    // 1 + q/2 + 3q^2/8 is exact to round-off (error 5q^3/16); the square root only if not.
    // (Lanes without a projection may divide by zero: their results are not selected)
    const bool proj = B.hasxi[p] != 0.0 && xn != 0.0 && m0 > 0.0;
    const double q = xn * xn / m0;
    const double sc = (q < 1e-4) ? 1.0 + q * (0.5 + 0.375 * q)
                                 : ((q < 1.0) ? std::sqrt(1.0 / (1.0 - q)) : 0.0);
    B.sc[p] = proj ? sc : 1.0;
    B.xn[p] = proj ? xn : 0.0;
    B.proj[p] = proj ? 1.0 : 0.0;
  }
}

/* ----------------------------------------------------------------------
   pass 2a of pair_loop: the common case of every pair of a batch -- an
   existing link, weld or attachment advanced by one step -- as straight-line
   arithmetic over the batch's arrays (branches are selects, so the loop
   vectorises).  The expressions and their order are those of the general
   path in pair_loop, so a pair gets the same numbers on either path.  elig
   is 1 where the result stands: linked and not breaking this step (else the
   general path redoes the pair from its state).
------------------------------------------------------------------------- */

template <int DIM, bool UNI> void PairMCA::batch_common(int n, double runi)
{
  constexpr bool D3 = (DIM == 3);
  Batch &B = *bat;
  const double dt = update->dt;
  const double G2 = 2.0 * mat.G;
  const double alpha = mat.alpha;
  const double s_link = mat.s0, s_weld = mat.wfac * mat.s0;
  const double dbar_u = runi + runi;
  const double A_u = pair_area(dbar_u, DIM), kr_u = rotational_stiffness(mat, A_u, dbar_u);
  const double LINK = FS::LINK, WELD = FS::WELD, ATTACH = FS::ATTACH;
  for (int p = 0; p < n; p++) {    // vectorised x4 (tests/mca/test_law_vectorised.py)
    const double kind = B.kind[p];
    const double n0 = B.n0[p], n1 = B.n1[p], n2 = D3 ? B.n2[p] : 0.0;
    const double ra = UNI ? runi : B.ra[p], rb = UNI ? runi : B.rb[p];
    const double dbar = UNI ? dbar_u : B.dbar[p];
    const double oa2 = B.oa2[p], ob2 = B.ob2[p];
    double wxn0, wxn1, wxn2 = 0.0;
    if (D3) {
      const double ws0 = ra * B.oa0[p] + rb * B.ob0[p], ws1 = ra * B.oa1[p] + rb * B.ob1[p],
                   ws2 = ra * oa2 + rb * ob2;
      wxn0 = ws1 * n2 - ws2 * n1;
      wxn1 = ws2 * n0 - ws0 * n2;
      wxn2 = ws0 * n1 - ws1 * n0;
    } else {
      const double ws2 = ra * oa2 + rb * ob2;
      wxn0 = -(ws2 * n1);
      wxn1 = ws2 * n0;
    }
    const double vr0 = B.dV0[p] - wxn0, vr1 = B.dV1[p] - wxn1;
    const double vr2 = D3 ? B.dV2[p] - wxn2 : 0.0;
    double xi0 = B.xi0[p], xi1 = B.xi1[p], xi2 = D3 ? B.xi2[p] : 0.0;
    const bool proj = B.proj[p] != 0.0;
    const double sc = B.sc[p], xn = B.xn[p];
    xi0 = proj ? sc * (xi0 - xn * n0) : xi0;
    xi1 = proj ? sc * (xi1 - xn * n1) : xi1;
    if (D3) xi2 = proj ? sc * (xi2 - xn * n2) : xi2;
    const double R0 = B.R0[p], R1 = B.R1[p], R2 = D3 ? B.R2[p] : 0.0;
    const double du0 = R0 - B.rp0[p] - dt * wxn0, du1 = R1 - B.rp1[p] - dt * wxn1;
    const double du2 = D3 ? R2 - B.rp2[p] - dt * wxn2 : 0.0;
    const double dun = D3 ? du0 * n0 + du1 * n1 + du2 * n2 : du0 * n0 + du1 * n1;
    xi0 += du0 - dun * n0;
    xi1 += du1 - dun * n1;
    if (D3) xi2 += du2 - dun * n2;
    double pn = B.pn[p];
    const double D0 = B.D0[p], D1 = B.D1[p], D3xy = B.D3[p];
    double th0 = 0.0, th1 = 0.0;
    if (D3) {
      const double D2 = B.D2[p], D4 = B.D4[p], D5 = B.D5[p];
      const double dsum = std::fabs(D0) + std::fabs(D1) + std::fabs(D2) + std::fabs(D3xy) +
          std::fabs(D4) + std::fabs(D5);
      const double Dn0 = D0 * n0 + D3xy * n1 + D4 * n2, Dn1 = D3xy * n0 + D1 * n1 + D5 * n2,
                   Dn2 = D4 * n0 + D5 * n1 + D2 * n2;
      const double nDn = n0 * Dn0 + n1 * Dn1 + n2 * Dn2;
      const bool pl = dsum > 0.0;
      pn = pl ? pn + nDn : pn;
      xi0 = pl ? xi0 - dbar * (Dn0 - nDn * n0) : xi0;
      xi1 = pl ? xi1 - dbar * (Dn1 - nDn * n1) : xi1;
      xi2 = pl ? xi2 - dbar * (Dn2 - nDn * n2) : xi2;
      th0 = B.th0[p] + dt * (B.ob0[p] - B.oa0[p]);
      th1 = B.th1[p] + dt * (B.ob1[p] - B.oa1[p]);
    } else {
      const double dsum = std::fabs(D0) + std::fabs(D1) + std::fabs(D3xy);
      const double Dn0 = D0 * n0 + D3xy * n1, Dn1 = D3xy * n0 + D1 * n1;
      const double nDn = n0 * Dn0 + n1 * Dn1;
      const bool pl = dsum > 0.0;
      pn = pl ? pn + nDn : pn;
      xi0 = pl ? xi0 - dbar * (Dn0 - nDn * n0) : xi0;
      xi1 = pl ? xi1 - dbar * (Dn1 - nDn * n1) : xi1;
    }
    const double th2 = B.th2[p] + dt * (ob2 - oa2);
    const double A = UNI ? A_u : pair_area(dbar, DIM);
    const double sf = G2 * B.idbar[p];
    const double sn = G2 * (B.eraw[p] - pn) + alpha * B.Xbar[p];
    const double t0 = sf * xi0, t1 = sf * xi1, t2v = D3 ? sf * xi2 : 0.0;
    const double t2 = D3 ? t0 * t0 + t1 * t1 + t2v * t2v : t0 * t0 + t1 * t1;
    const double strength = (kind == LINK) ? s_link : s_weld;
    const double tp = (sn > 0.0) ? sn : 0.0;    // link_breaks_sq
    const bool brk = (kind != ATTACH) && (tp * tp + 3.0 * t2 > strength * strength);
    const double cd = B.cd[p], cr = B.cr[p];
    const double kr = UNI ? kr_u : rotational_stiffness(mat, A, dbar);
    const bool linked0 = (kind == LINK) || (kind == WELD) || (kind == ATTACH);
    B.elig[p] = (linked0 && !brk) ? 1.0 : 0.0;
    B.xi0n[p] = xi0;
    B.xi1n[p] = xi1;
    B.pnn[p] = pn;
    B.th2n[p] = th2;
    B.Fe0[p] = A * (sn * n0 + t0);
    B.Fe1[p] = A * (sn * n1 + t1);
    B.Fd0[p] = cd * vr0;
    B.Fd1[p] = cd * vr1;
    B.Ma2[p] = kr * th2 + cr * (ob2 - oa2);
    if (D3) {
      B.xi2n[p] = xi2;
      B.th0n[p] = th0;
      B.th1n[p] = th1;
      B.Fe2[p] = A * (sn * n2 + t2v);
      B.Fd2[p] = cd * vr2;
      B.Ma0[p] = kr * th0 + cr * (B.ob0[p] - B.oa0[p]);
      B.Ma1[p] = kr * th1 + cr * (B.ob1[p] - B.oa1[p]);
    }
    // (the expressions of the general path's tail, pair_loop)
    const double Fe0 = B.Fe0[p], Fe1 = B.Fe1[p], Fe2 = D3 ? B.Fe2[p] : 0.0;
    const double F0 = Fe0 + B.Fd0[p], F1 = Fe1 + B.Fd1[p], F2 = D3 ? Fe2 + B.Fd2[p] : 0.0;
    const double si = (B.ia[p] != 0.0) ? 1.0 : -1.0;
    B.F0[p] = F0;
    B.F1[p] = F1;
    B.nxF2[p] = n0 * F1 - n1 * F0;
    B.L0[p] = n0 * Fe0;
    B.L1[p] = n1 * Fe1;
    B.L3[p] = 0.5 * (n0 * Fe1 + n1 * Fe0);
    B.Fs0[p] = si * F0;
    B.Fs1[p] = si * F1;
    B.Ms2[p] = si * B.Ma2[p];
    if (D3) {
      B.F2[p] = F2;
      B.nxF0[p] = n1 * F2 - n2 * F1;
      B.nxF1[p] = n2 * F0 - n0 * F2;
      B.L2[p] = n2 * Fe2;
      B.L4[p] = 0.5 * (n0 * Fe2 + n2 * Fe0);
      B.L5[p] = 0.5 * (n1 * Fe2 + n2 * Fe1);
      B.Fs2[p] = si * F2;
      B.Ms0[p] = si * B.Ma0[p];
      B.Ms1[p] = si * B.Ma1[p];
    }
  }
}

/* ----------------------------------------------------------------------
   Love-Weber stress of automaton i, its mean-stress term X and the radial
   return (mca_law.h, rule 7).  2D is plane strain: sigma_zz follows from the
   in-plane state, sigma_zz = alpha X - 2G eps_p_zz with X = in-plane mean -
   G eps_p_zz (the combination for which the lattice reproduces plane-strain
   Hooke's law with plastic strain).  Then, automaton by automaton in one pass
   over its rows: the counters into sums (cf cb lb wf, in the automata's
   order), the pair loop's force and torque sums into f and torque, the
   committed step's forces (stored, or restored by a re-evaluation), the
   state and the per-atom output, and the row of sums cleared for the next
   step (its last reader; was a separate pass before the pair loop, which
   brought every row in from memory once more).
------------------------------------------------------------------------- */

template <int DIM>
void PairMCA::automata_update(int i0, int na, bool advance, bool restore, double iVuni,
                              double *sums)
{
  // (rows of contiguous per-atom arrays)
  double *autom0 = fix->autom[0];
  double *sacc_ = sacc[0];
  const double *radius = atom->radius;
  AutomBatch &A = *abat;
  for (int q = 0; q < na; q++) {
    const int i = i0 + q;
    const double *acc = sacc_ + SR * (bigint) i;
    const double *am = autom0 + (bigint) i * FS::NAUTO;
    const double iV = (iVuni > 0.0) ? iVuni : 1.0 / automaton_volume(2.0 * radius[i], DIM);
    A.acc[0][q] = acc[C_L0];
    A.acc[1][q] = acc[C_L1];
    A.acc[2][q] = acc[C_L2];
    A.acc[3][q] = acc[C_L3];
    A.acc[4][q] = acc[C_L4];
    A.acc[5][q] = acc[C_L5];
    A.iV[q] = iV;
    A.ept2[q] = am[FS::A_EPT + 2];
    A.ep[q] = am[FS::A_EEQ];
  }
  // the stress (rule 7 in mca_law.h: radial_return, as selects; the same expressions)
  const double G = mat.G, alpha = mat.alpha, H = mat.H, sy0 = mat.sy, s0 = mat.s0;
  const double inv_3GH = mat.inv_3GH, inv_3G = mat.inv_3G;
  for (int q = 0; q < na; q++) {    // vectorised x2 (tests/mca/test_law_vectorised.py)
    const double iV = A.iV[q];
    double sig0, sig1, sig2, sig3, sig4, sig5, X;
    if (DIM == 2) {
      sig0 = A.acc[0][q] * iV;
      sig1 = A.acc[1][q] * iV;
      sig3 = A.acc[3][q] * iV;
      sig4 = sig5 = 0.0;
      X = 0.5 * (sig0 + sig1) - G * A.ept2[q];
      sig2 = alpha * X - 2.0 * G * A.ept2[q];
    } else {
      sig0 = A.acc[0][q] * iV;
      sig1 = A.acc[1][q] * iV;
      sig2 = A.acc[2][q] * iV;
      sig3 = A.acc[3][q] * iV;
      sig4 = A.acc[4][q] * iV;
      sig5 = A.acc[5][q] * iV;
      X = (sig0 + sig1 + sig2) / 3.0;
    }
    const double ep = A.ep[q];
    const double p = (sig0 + sig1 + sig2) / 3.0;    // von_mises
    const double d0 = sig0 - p, d1 = sig1 - p, d2 = sig2 - p;
    const double s_eq =
        std::sqrt(1.5 * (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (sig3 * sig3 + sig4 * sig4 + sig5 * sig5)));
    const double ys = sy0 + H * ep;    // yield_stress
    const double sy = (ys < s0) ? ys : s0;
    const bool elastic = (s_eq <= sy) | (s_eq <= 0.0);
    double dg = (s_eq - sy) * inv_3GH;
    const double ys1 = sy0 + H * (ep + dg);
    dg = (((ys1 < s0) ? ys1 : s0) >= s0) ? (s_eq - s0) * inv_3G : dg;
    dg = (dg < 0.0) ? 0.0 : dg;
    const double is = 1.0 / s_eq;    // (elastic lanes may divide by zero: not selected)
    const double f = 1.0 - 3.0 * G * dg * is;
    const double c = 1.5 * dg * is;
    A.dg[q] = elastic ? 0.0 : dg;
    A.X[q] = X;
    A.seq[q] = elastic ? s_eq : f * s_eq;
    A.dep[0][q] = elastic ? 0.0 : c * d0;
    A.dep[1][q] = elastic ? 0.0 : c * d1;
    A.dep[2][q] = elastic ? 0.0 : c * d2;
    A.dep[3][q] = elastic ? 0.0 : c * sig3;
    A.dep[4][q] = elastic ? 0.0 : c * sig4;
    A.dep[5][q] = elastic ? 0.0 : c * sig5;
    A.sig[0][q] = elastic ? sig0 : f * d0 + p;
    A.sig[1][q] = elastic ? sig1 : f * d1 + p;
    A.sig[2][q] = elastic ? sig2 : f * d2 + p;
    A.sig[3][q] = elastic ? sig3 : f * sig3 + 0.0;
    A.sig[4][q] = elastic ? sig4 : f * sig4 + 0.0;
    A.sig[5][q] = elastic ? sig5 : f * sig5 + 0.0;
  }
  double **f = atom->f, **torque = atom->torque;
  const int nclear = (DIM == 3) ? (int) SR : (int) C_F2;
  for (int q = 0; q < na; q++) {
    const int i = i0 + q;
    double *am = autom0 + (bigint) i * FS::NAUTO;
    double *acc = sacc_ + SR * (bigint) i;
    // the counters, the pair loop's sums into f and torque (cleared before the pair style:
    // 0 + s is s, the number the sums into f itself gave; in 2D the z force and the x, y
    // torques are +0 and their sums never touched), the committed step's pair forces
    sums[0] += am[FS::A_CF];
    sums[1] += am[FS::A_CB];
    sums[2] += am[FS::A_LB];
    sums[3] += am[FS::A_WF];
    double *fi = f[i], *ti = torque[i];
    if (!restore) {
      fi[0] += acc[C_F0];
      fi[1] += acc[C_F1];
      ti[2] += acc[C_T2];
      if (DIM == 3) {
        fi[2] += acc[C_F2];
        ti[0] += acc[C_T0];
        ti[1] += acc[C_T1];
      }
    }
    if (advance) {
      for (int c = 0; c < 3; c++) {
        am[FS::A_F + c] = fi[c];
        am[FS::A_T + c] = ti[c];
      }
    } else if (restore) {
      for (int c = 0; c < 3; c++) {
        fi[c] = am[FS::A_F + c];
        ti[c] = am[FS::A_T + c];
      }
    }
    if (advance) {
      for (int c = 0; c < 6; c++) {
        am[FS::A_DEP + c] = A.dep[c][q];
        am[FS::A_EPT + c] += A.dep[c][q];
      }
      am[FS::A_EEQ] += A.dg[q];
      am[FS::A_XU] = am[FS::A_X];
      am[FS::A_X] = A.X[q];
    }
    // (stress, eps_eq, links, cross links, von Mises stress: the first NOUT values of the row
    // are the per-atom output, f_mca_state and compute mca/atom, read in place.  Until
    // 2026-12-06 they were also streamed into a separate output array every step: about 5 %
    // of the 2D systems' run time)
    for (int c = 0; c < 6; c++) am[FS::A_SIG + c] = A.sig[c][q];
    am[FS::A_NL] = acc[C_NL];
    am[FS::A_NC] = acc[C_NC];
    am[FS::A_SEQ] = A.seq[q];
    // (the row's last reader)
    for (int k = 0; k < nclear; k++) acc[k] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

int PairMCA::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  int m = 0;
  for (int q = 0; q < n; q++) {
    const double *xq = xo[list[q]];
    for (int c = 0; c < PR; c++) buf[m++] = xq[c];
  }
  return m;
}

void PairMCA::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    double *xq = xo[i];
    for (int c = 0; c < PR; c++) xq[c] = buf[m++];
  }
}

/* ---------------------------------------------------------------------- */

void PairMCA::write_restart_settings(FILE *fp)
{
  fwrite(&link_init, sizeof(int), 1, fp);
  fwrite(&link_tol, sizeof(double), 1, fp);
  fwrite(&cutfac, sizeof(double), 1, fp);
}

void PairMCA::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) {
    utils::sfread(FLERR, &link_init, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &link_tol, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &cutfac, sizeof(double), 1, fp, nullptr, error);
  }
  MPI_Bcast(&link_init, 1, MPI_INT, 0, world);
  MPI_Bcast(&link_tol, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&cutfac, 1, MPI_DOUBLE, 0, world);
}

void PairMCA::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  double v[10] = {mat.G, mat.nu, mat.sy, mat.s0, mat.H, mat.mu, mat.eta, mat.wfac, mat.wonset, mat.damp};
  fwrite(v, sizeof(double), 10, fp);
}

void PairMCA::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  double v[10];
  if (comm->me == 0) utils::sfread(FLERR, v, sizeof(double), 10, fp, nullptr, error);
  MPI_Bcast(v, 10, MPI_DOUBLE, 0, world);
  mat.G = v[0]; mat.nu = v[1]; mat.sy = v[2]; mat.s0 = v[3]; mat.H = v[4];
  mat.mu = v[5]; mat.eta = v[6]; mat.wfac = v[7]; mat.wonset = v[8]; mat.damp = v[9];
  mat.dim = domain->dimension;
  mat.derive();
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 1;
  coeffset = 1;
}

double PairMCA::memory_usage()
{
  return (double) maxflat * (5 * sizeof(int)) + (double) maxpsc * sizeof(double) +
      (double) maxsacc * SR * sizeof(double) +
      (double) maxxo * (PR * sizeof(double) + 3 * sizeof(int)) + (double) maxsperm * sizeof(int) +
      (bat ? sizeof(Batch) : 0) + (abat ? sizeof(AutomBatch) : 0);
}
