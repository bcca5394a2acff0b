/* -*- c++ -*- ---------------------------------------------------------
   tribolmp MCA plugin: memory hints for the large per-atom arrays.

   The pair state (fix mca/state's slots: maxpartner x 12 doubles per automaton, 1.9 kB in 3D)
   and the per-automaton rows of pair mca span tens of MB in a friction system of 10^4-10^5
   automata, and the pair loop visits each automaton's rows in turn: with 4 kB pages nearly every
   automaton costs a TLB miss.  Where the kernel makes transparent huge pages only on request
   (/sys/kernel/mm/transparent_hugepage/enabled = madvise, common on servers), asking for them
   for these arrays before they are first written lets the kernel back them with 2 MB pages.  A
   hint only: it changes no number, and where it is not honoured nothing changes.
------------------------------------------------------------------------- */

#ifndef TRIBOLMP_MCA_MEMORY_H
#define TRIBOLMP_MCA_MEMORY_H

#include <cstddef>
#include <cstdint>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace MCAMemory {

// ask for huge pages for the whole pages inside [p, p + bytes); only for arrays of >= 4 MB,
// smaller ones rarely span a 2 MB-aligned page
inline void hugepage_hint(void *p, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (!p || bytes < (std::size_t(4) << 20)) return;
  const std::uintptr_t page = 4096;
  const std::uintptr_t a = (reinterpret_cast<std::uintptr_t>(p) + page - 1) & ~(page - 1);
  const std::uintptr_t e = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(page - 1);
  if (e > a) madvise(reinterpret_cast<void *>(a), e - a, MADV_HUGEPAGE);
#else
  (void) p;
  (void) bytes;
#endif
}

}    // namespace MCAMemory

#endif
